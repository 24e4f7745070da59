// The hosts that earlier bakes lost, left out of the next bakes' host files
// for a while (mpi/host_roster.h).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "lightmass_server/mpi/host_roster.h"

namespace lc::bake {
namespace {
namespace fs = std::filesystem;
using Clock = HostRoster::Clock;

fs::path hostfile_with(const std::string& text) {
    const fs::path path = fs::temp_directory_path() / ("host_roster_test_" + std::to_string(getpid()));
    std::ofstream(path) << text;
    return path;
}

constexpr const char* kHosts = "# the bake hosts\nnode1 slots=2\nnode2 slots=2 # rack 2\n\nnode3\n";

TEST(HostRoster, ReadsTheHostOfAHostFileLine) {
    EXPECT_EQ(host_of_hostfile_line("node1 slots=2"), "node1");
    EXPECT_EQ(host_of_hostfile_line("  node2\tslots=4 # rack"), "node2");
    EXPECT_EQ(host_of_hostfile_line("# node3"), "");
    EXPECT_EQ(host_of_hostfile_line(""), "");
}

TEST(HostRoster, LeavesALostHostOutUntilItsPauseHasPassed) {
    const fs::path path = hostfile_with(kHosts);
    HostRoster roster(std::chrono::minutes(10));
    const Clock::time_point lost = Clock::now();
    roster.mark_lost("node2", lost);
    Result<std::string> during = roster.hostfile_without_lost(path, lost + std::chrono::minutes(9));
    ASSERT_TRUE(during.ok()) << during.error();
    EXPECT_EQ(*during, "# the bake hosts\nnode1 slots=2\n\nnode3\n");
    Result<std::string> after = roster.hostfile_without_lost(path, lost + std::chrono::minutes(10));
    ASSERT_TRUE(after.ok()) << after.error();
    EXPECT_EQ(*after, std::string(kHosts));
    fs::remove(path);
}

TEST(HostRoster, RefusesWhenEveryHostIsLostNamingThem) {
    const fs::path path = hostfile_with("node1\nnode2\n");
    HostRoster roster;
    const Clock::time_point now = Clock::now();
    roster.mark_lost("node2", now);
    roster.mark_lost("node1", now);
    Result<std::string> kept = roster.hostfile_without_lost(path, now);
    ASSERT_FALSE(kept.ok());
    EXPECT_NE(kept.error().find("node1, node2"), std::string::npos) << kept.error();
    fs::remove(path);
}

TEST(HostRoster, AMissingHostFileIsAnErrorNamingIt) {
    HostRoster roster;
    Result<std::string> kept = roster.hostfile_without_lost("/nonexistent/hosts.txt");
    ASSERT_FALSE(kept.ok());
    EXPECT_NE(kept.error().find("/nonexistent/hosts.txt"), std::string::npos) << kept.error();
}

}  // namespace
}  // namespace lc::bake
