// The server as a service: the shipped configuration (packaging/) names every
// flag of the server and is read by it, a flag on the command line wins over
// the file, and the systemd unit verifies (systemd-analyze, where present).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "test_paths.h"

namespace lc {
namespace {
namespace fs = std::filesystem;

struct CommandRun {
    int exit_code = -1;
    std::string output;
};

CommandRun run(const std::string& command_line, const fs::path& dir) {
    const fs::path log = dir / "out.txt";
    const int status = std::system((command_line + " > " + log.string() + " 2>&1").c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::read_text(log)};
}

// The keys of `flag = value` lines, commented out or not.
std::set<std::string> config_keys(const std::string& text) {
    static const std::regex line(R"(^#?\s*([a-z][a-z0-9-]*)\s*=)");
    std::set<std::string> keys;
    std::istringstream lines(text);
    for (std::string l; std::getline(lines, l);)
        if (std::smatch m; std::regex_search(l, m, line)) keys.insert(m[1]);
    return keys;
}

class ServiceConfig : public ::testing::Test {
protected:
    void SetUp() override { dir_ = test::make_temp_dir("service-config"); }
    void TearDown() override { fs::remove_all(dir_); }
    std::string server() const { return (test::bin_dir() / "lightmass_server").string(); }
    fs::path shipped() const { return test::source_dir() / "packaging" / "lightmass_server.conf"; }
    fs::path dir_;
};

TEST_F(ServiceConfig, TheShippedFileNamesEveryFlagOfTheServer) {
    const CommandRun printed = run(server() + " --print-config", dir_);
    ASSERT_EQ(printed.exit_code, 0) << printed.output;
    const std::set<std::string> flags = config_keys(printed.output);
    EXPECT_GE(flags.size(), 25u) << printed.output;
    EXPECT_EQ(flags.count("print-config"), 0u);
    EXPECT_EQ(config_keys(test::read_text(shipped())), flags)
        << "packaging/lightmass_server.conf must list every flag `lightmass_server --print-config` prints";
}

TEST_F(ServiceConfig, TheServerReadsTheFileAndTheCommandLineWins) {
    const CommandRun read = run(server() + " --config " + shipped().string() + " --print-config", dir_);
    ASSERT_EQ(read.exit_code, 0) << read.output;
    EXPECT_NE(read.output.find("listen=\"127.0.0.1:7540\""), std::string::npos) << read.output;
    EXPECT_NE(read.output.find("mpi-work-dir=\"/var/lib/lightcuts/mpi-jobs\""), std::string::npos) << read.output;

    const fs::path mine = dir_ / "mine.conf";
    std::ofstream(mine) << "max-connections = 7\nmpi-arg = [\"--mca\", \"btl\", \"self,tcp\"]\n";
    const CommandRun both = run(server() + " --config " + mine.string() + " --max-connections 9 --print-config", dir_);
    ASSERT_EQ(both.exit_code, 0) << both.output;
    EXPECT_NE(both.output.find("max-connections=9"), std::string::npos) << both.output;
    EXPECT_NE(both.output.find("mpi-arg=[\"--mca\", \"btl\", \"self,tcp\"]"), std::string::npos) << both.output;

    const CommandRun missing = run(server() + " --config " + (dir_ / "none.conf").string(), dir_);
    EXPECT_NE(missing.exit_code, 0);
    EXPECT_NE(missing.output.find("none.conf"), std::string::npos) << missing.output;
}

TEST_F(ServiceConfig, TheSystemdUnitVerifies) {
    if (std::system("command -v systemd-analyze > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "systemd-analyze is not installed: the unit is not verified";
    // The installed unit starts /usr/bin/lightmass_server; here the built one stands in for it.
    std::string unit = test::read_text(test::source_dir() / "packaging" / "lightmass_server.service");
    ASSERT_NE(unit.find("ExecStart=/usr/bin/lightmass_server "), std::string::npos);
    unit.replace(unit.find("/usr/bin/lightmass_server"), 25, server());
    const fs::path copy = dir_ / "lightmass_server.service";
    std::ofstream(copy) << unit;
    const CommandRun verified = run("systemd-analyze verify " + copy.string(), dir_);
    EXPECT_EQ(verified.exit_code, 0) << verified.output;
    EXPECT_EQ(verified.output, "") << "systemd-analyze has remarks on packaging/lightmass_server.service";
    for (const char* hardening : {"DynamicUser=yes", "NoNewPrivileges=yes", "StateDirectory=lightcuts"})
        EXPECT_NE(unit.find(hardening), std::string::npos) << hardening;
}

}  // namespace
}  // namespace lc
