#pragma once
// Where tests find the bundled data, the shared scenes and the built programs.
#include <filesystem>
#include <string>

namespace lc::test {

std::filesystem::path source_dir();
std::filesystem::path data_dir();
std::filesystem::path bin_dir();
// ../shared/scenes, or an empty path when it is absent (a user's fresh clone).
std::filesystem::path shared_scenes_dir();
// A fresh empty temporary directory, unique per test.
std::filesystem::path make_temp_dir(const std::string& label);
// A file's bytes (a log, a JSON, a glTF), empty when it cannot be read.
std::string read_text(const std::filesystem::path& path);

}  // namespace lc::test

// Skips the current test with a clear message when ../shared/scenes is absent.
#define LC_REQUIRE_SHARED_SCENES()                                                          \
    do {                                                                                    \
        if (::lc::test::shared_scenes_dir().empty())                                        \
            GTEST_SKIP() << "../shared/scenes is absent (fresh clone): skipping scene test"; \
    } while (0)
