// Every program answers --version with its name and the project's version
// (CMake's project(VERSION), through lightcuts/version.h), and exits 0.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "lightcuts/version.h"
#include "test_paths.h"

namespace lc {
namespace {

struct VersionRun {
    int exit_code = -1;
    std::string output;
};

VersionRun run_version(const std::string& program) {
    const auto dir = test::make_temp_dir("version");
    const auto log = dir / "out.txt";
    const std::string command = (test::bin_dir() / program).string() + " --version > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    VersionRun run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::read_text(log)};
    std::filesystem::remove_all(dir);
    return run;
}

TEST(ProgramVersion, EveryProgramPrintsTheProjectVersion) {
    EXPECT_STRNE(kVersion, "");
    for (const std::string program : {"lightmass_server", "editor_client", "lightmass_rank"}) {
        SCOPED_TRACE(program);
        if (program == "lightmass_rank" && !std::filesystem::exists(test::bin_dir() / program)) {
            std::printf("lightmass_rank was not built (no MPI): its --version is not checked\n");
            continue;
        }
        const VersionRun run = run_version(program);
        EXPECT_EQ(run.exit_code, 0) << run.output;
        EXPECT_EQ(run.output, program + " " + kVersion + "\n");
    }
}

}  // namespace
}  // namespace lc
