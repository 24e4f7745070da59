#include "lightmass_server/net/auth_token.h"

#include <fstream>
#include <sstream>

namespace lc::bake {

Result<std::string> read_token_file(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) return make_error("cannot read token file '" + path.string() + "'");
    std::string line;
    std::getline(in, line);
    const char* space = " \t\r\n";
    size_t first = line.find_first_not_of(space);
    size_t last = line.find_last_not_of(space);
    std::string token = first == std::string::npos ? "" : line.substr(first, last - first + 1);
    if (token.empty()) return make_error("token file '" + path.string() + "' is empty");
    if (token.size() < 16)
        return make_error("token in '" + path.string() + "' is too short (" +
                          std::to_string(token.size()) + " characters, at least 16 required)");
    return token;
}

bool tokens_equal(std::string_view expected, std::string_view given) {
    // Accumulate differences over the longer length so timing does not reveal
    // the position of the first mismatch.
    size_t n = expected.size() > given.size() ? expected.size() : given.size();
    unsigned diff = static_cast<unsigned>(expected.size() ^ given.size());
    for (size_t i = 0; i < n; ++i) {
        unsigned char a = i < expected.size() ? static_cast<unsigned char>(expected[i]) : 0;
        unsigned char b = i < given.size() ? static_cast<unsigned char>(given[i]) : 0;
        diff |= static_cast<unsigned>(a ^ b);
    }
    return diff == 0 && !expected.empty();
}

}  // namespace lc::bake
