#include "protocol/token_file.h"

#include <fstream>
#include <iterator>

namespace lc {

Result<std::string> read_token_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error("cannot read token file '" + path.string() + "'");
    std::string bytes;
    bytes.resize(kMaxTokenFileBytes + 1);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    bytes.resize(static_cast<size_t>(in.gcount()));
    if (bytes.size() > kMaxTokenFileBytes) {
        return make_error("token file '" + path.string() + "' is over " + std::to_string(kMaxTokenFileBytes) +
                          " bytes (a token is one line)");
    }
    const std::string line = bytes.substr(0, bytes.find('\n'));
    const char* space = " \t\r\n";
    const size_t first = line.find_first_not_of(space);
    const size_t last = line.find_last_not_of(space);
    const std::string token = first == std::string::npos ? "" : line.substr(first, last - first + 1);
    if (token.empty()) return make_error("token file '" + path.string() + "' is empty");
    if (token.size() < kMinTokenLength) {
        return make_error("token in '" + path.string() + "' is too short (" + std::to_string(token.size()) +
                          " characters, at least " + std::to_string(kMinTokenLength) + " required)");
    }
    return token;
}

}  // namespace lc
