#include "test_paths.h"

#include <atomic>
#include <fstream>
#include <iterator>
#include <chrono>
#include <unistd.h>

namespace lc::test {

std::filesystem::path source_dir() { return LC_SOURCE_DIR; }
std::filesystem::path data_dir() { return LC_TEST_DATA_DIR; }
std::filesystem::path bin_dir() { return LC_BIN_DIR; }

std::filesystem::path shared_scenes_dir() {
    std::filesystem::path dir = LC_SHARED_SCENES_DIR;
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) return {};
    return std::filesystem::weakly_canonical(dir, ec);
}

std::filesystem::path make_temp_dir(const std::string& label) {
    static std::atomic<int> counter{0};
    auto dir = std::filesystem::temp_directory_path() /
               ("lc-test-" + label + "-" + std::to_string(::getpid()) + "-" +
                std::to_string(counter++));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace lc::test
