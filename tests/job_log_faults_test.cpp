// mpirun's log read for the host a bake over several machines lost
// (mpi/job_log_faults.h). The logs are Open MPI 4.1.4's own text, recorded
// from jobs over network namespaces (tests/hosts/multi_host_bake_test.sh).
#include <gtest/gtest.h>

#include "lightmass_server/mpi/job_log_faults.h"

namespace lc::bake {
namespace {

constexpr const char* kLostDaemon =
    R"(--------------------------------------------------------------------------
ORTE has lost communication with a remote daemon.

  HNP daemon   : [[10184,0],0] on node lcx1
  Remote daemon: [[10184,0],1] on node lcx2

This is usually due to either a failure of the TCP network
connection to the node, or possibly an internal failure of
the daemon itself. We cannot recover from this failure, and
therefore will terminate the job.
--------------------------------------------------------------------------
)";

constexpr const char* kRankKilled =
    R"(--------------------------------------------------------------------------
Primary job  terminated normally, but 1 process returned
a non-zero exit code. Per user-direction, the job has been aborted.
--------------------------------------------------------------------------
--------------------------------------------------------------------------
mpirun noticed that process rank 1 with PID 14788 on node lcx3 exited on signal 9 (Killed).
--------------------------------------------------------------------------
)";

constexpr const char* kNoConnectionBack = R"(------------------------------------------------------------
A process or daemon was unable to complete a TCP connection
to another process:
  Local host:    lcx2
  Remote host:   lcx1
This is usually caused by a firewall on the remote host. Please
check that any firewall (e.g., iptables) has been disabled and
try again.
------------------------------------------------------------
--------------------------------------------------------------------------
ORTE was unable to reliably start one or more daemons.
)";

TEST(JobLogFaults, ALostDaemonNamesItsHostAsLost) {
    const std::optional<HostFault> fault = host_fault_in_log(kLostDaemon);
    ASSERT_TRUE(fault.has_value());
    EXPECT_EQ(fault->host, "lcx2");
    EXPECT_TRUE(fault->host_lost);
    EXPECT_NE(fault->text.find("host lcx2 stopped answering"), std::string::npos) << fault->text;
    EXPECT_EQ(fault->text.find('\n'), std::string::npos) << "one line";
}

TEST(JobLogFaults, AKilledRankNamesItsHostWithoutLosingIt) {
    const std::optional<HostFault> fault = host_fault_in_log(kRankKilled);
    ASSERT_TRUE(fault.has_value());
    EXPECT_EQ(fault->host, "lcx3");
    EXPECT_FALSE(fault->host_lost);
    EXPECT_EQ(fault->text, "rank 1 on host lcx3 exited on signal 9 (Killed)");
}

TEST(JobLogFaults, ADaemonThatCannotConnectBackNamesItsHostAndMpirunsHost) {
    const std::optional<HostFault> fault = host_fault_in_log(kNoConnectionBack);
    ASSERT_TRUE(fault.has_value());
    EXPECT_EQ(fault->host, "lcx2");
    EXPECT_TRUE(fault->host_lost);
    EXPECT_NE(fault->text.find("could not connect back to mpirun on lcx1"), std::string::npos) << fault->text;
}

TEST(JobLogFaults, SshThatCannotReachAHostNamesIt) {
    const std::optional<HostFault> fault =
        host_fault_in_log("ssh: connect to host node7 port 22: Connection timed out\r\n");
    ASSERT_TRUE(fault.has_value());
    EXPECT_EQ(fault->host, "node7");
    EXPECT_EQ(fault->text, "host node7 did not answer ssh: port 22: Connection timed out");
    const std::optional<HostFault> unknown =
        host_fault_in_log("ssh: Could not resolve hostname nodex: Name or service not known\n");
    ASSERT_TRUE(unknown.has_value());
    EXPECT_EQ(unknown->host, "nodex");
}

// When a host goes, its ranks die with it: the host's loss is the line to show.
TEST(JobLogFaults, TheHostsLossComesBeforeTheRanksThatDiedWithIt) {
    const std::optional<HostFault> fault = host_fault_in_log(std::string(kRankKilled) + kLostDaemon);
    ASSERT_TRUE(fault.has_value());
    EXPECT_EQ(fault->host, "lcx2");
    EXPECT_TRUE(fault->host_lost);
}

TEST(JobLogFaults, ALogWithoutAHostFaultGivesNothing) {
    EXPECT_FALSE(host_fault_in_log("").has_value());
    EXPECT_FALSE(
        host_fault_in_log("MPI_ABORT was invoked on rank 0 in communicator MPI_COMM_WORLD\n").has_value());
    EXPECT_FALSE(host_fault_in_log("ORTE has lost communication with a remote daemon.\n").has_value());
}

}  // namespace
}  // namespace lc::bake
