// What the server adds to a local MPI launch by itself (local_slots.h), and
// the launcher's known refusals told in one line naming the flag that fixes
// them (mpi_failure.h), from Open MPI 4.1's own words.
#include <gtest/gtest.h>

#include <string>

#include "lightmass_server/mpi/local_slots.h"
#include "lightmass_server/mpi/mpi_failure.h"

namespace lc::bake {
namespace {

TEST(LocalLaunch, MoreRanksThanCoresOnThisMachineOversubscribesAndSaysSo) {
    MpiLaunchOptions mpi;
    const LocalLaunch three_on_two = local_launch(mpi, 3, 2);
    EXPECT_EQ(three_on_two.extra_args, std::vector<std::string>{"--oversubscribe"});
    EXPECT_EQ(three_on_two.note,
              "mpi: 3 ranks on this machine's 2 cores: oversubscribed (--mpi-oversubscribe off refuses instead)");
    const LocalLaunch two_on_two = local_launch(mpi, 2, 2);
    EXPECT_TRUE(two_on_two.extra_args.empty());
    EXPECT_TRUE(two_on_two.note.empty());
}

TEST(LocalLaunch, AHostfileOffOrTheUsersOwnFlagAddNothing) {
    MpiLaunchOptions mpi;
    mpi.hostfile = "/etc/lightcuts/hosts";  // the slots are the cluster's, not this machine's
    EXPECT_TRUE(local_launch(mpi, 64, 2).extra_args.empty());
    mpi.hostfile.clear();
    mpi.oversubscribe = "off";
    EXPECT_TRUE(local_launch(mpi, 3, 2).extra_args.empty());
    mpi.oversubscribe = "auto";
    mpi.launcher_args = {"--oversubscribe"};
    EXPECT_TRUE(local_launch(mpi, 3, 2).extra_args.empty()) << "added twice";
    mpi.launcher_args.clear();
    mpi.oversubscribe = "on";
    mpi.hostfile = "/etc/lightcuts/hosts";
    const LocalLaunch forced = local_launch(mpi, 2, 16);
    EXPECT_EQ(forced.extra_args, std::vector<std::string>{"--oversubscribe"});
    EXPECT_EQ(forced.note, "mpi: 2 ranks, oversubscribed (--mpi-oversubscribe on)");
}

TEST(MpiFailure, TooFewSlotsNamesTheOversubscribeFlag) {
    const std::string log =
        "--------------------------------------------------------------------------\n"
        "There are not enough slots available in the system to satisfy the 3\n"
        "slots that were requested by the application:\n\n  lightmass_rank\n\n"
        "Either request fewer slots for your application, or make more slots\navailable for use.\n";
    const std::string line = explain_mpi_failure(log, 3);
    EXPECT_EQ(line.find('\n'), std::string::npos);
    EXPECT_NE(line.find("fewer slots than the 3 ranks"), std::string::npos) << line;
    EXPECT_NE(line.find("--mpi-oversubscribe on"), std::string::npos) << line;
    EXPECT_NE(line.find("--server-arg=--mpi-oversubscribe=on"), std::string::npos) << line;
}

TEST(MpiFailure, RootAndAMissingRankProgramAreNamedAndOthersAreLeftToTheLog) {
    const std::string root = explain_mpi_failure("mpirun has detected an attempt to run as root.\n", 2);
    EXPECT_NE(root.find("--mpi-arg=--allow-run-as-root"), std::string::npos) << root;
    const std::string missing = explain_mpi_failure(
        "mpirun was unable to find the specified executable file, and therefore\ndid not launch the job.\n", 2);
    EXPECT_NE(missing.find("--mpi-rank-program PATH"), std::string::npos) << missing;
    EXPECT_EQ(explain_mpi_failure("mpirun noticed that process rank 1 exited on signal 9 (Killed).\n", 2), "");
}

}  // namespace
}  // namespace lc::bake
