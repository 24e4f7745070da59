// Dump reader: any file is read or refused without a crash; a dump that reads
// writes back to the same bytes. read_dump takes a path, so each input goes
// through a file of this process's own.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "protocol/dump.h"

namespace {

std::filesystem::path scratch(const char* what) {
    return std::filesystem::temp_directory_path() /
           ("lc-dump-fuzz-" + std::to_string(::getpid()) + "-" + what);
}

std::vector<uint8_t> file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using lc::fuzz::check;
    static const std::filesystem::path input = scratch("input.dump");
    static const std::filesystem::path output = scratch("output.dump");
    {
        std::ofstream out(input, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    lc::Result<lc::ChannelDump> dump = lc::read_dump(input);
    if (!dump) {
        check(!dump.error().empty(), "a refused dump says why");
        return 0;
    }
    check(lc::write_dump(output, *dump).ok(), "a dump that reads can be written");
    check(file_bytes(output) == std::vector<uint8_t>(data, data + size),
          "write(read(x)) == x");
    return 0;
}
