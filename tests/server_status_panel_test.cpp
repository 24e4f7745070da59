// The editor's server panel: its lines from a status reply, its one line for a
// server that refuses or cannot be reached, and the poller that asks off the
// render thread (here against a port nobody listens on).
#include <gtest/gtest.h>

#include <thread>

#include "editor_client/editor/server_status_poller.h"
#include "protocol/asio.h"

namespace lc::client {
namespace {

StatusReplyMsg busy_server() {
    StatusReplyMsg s;
    s.version = "lightmass_server 9.9.9";
    s.uptime_seconds = 3725.0;
    s.bakes = {BakeStatusEntry{3, 1, "running", "indirect", 42.5f, 4},
               BakeStatusEntry{5, 2, "queued", "", 0.0f, 0}};
    s.memory_budget_bytes = uint64_t{1024} << 20;
    s.memory_held_bytes = uint64_t{256} << 20;
    s.connections = 3;
    s.max_connections = 16;
    s.max_concurrent_bakes = 1;
    s.max_bake_seconds = 600;
    s.mpi_launcher = "srun";
    s.mpi_max_ranks = 8;
    return s;
}

TEST(ServerStatusPanel, LinesSayVersionBakesBudgetLimitsAndMpi) {
    const std::vector<std::string> lines = server_panel_lines(busy_server());
    const std::vector<std::string> expected = {
        "lightmass_server 9.9.9, up 3725 s",
        "connections: 3 of 16",
        "bakes: 1 running, 1 queued, 0 streaming; 1 big bakes at once, each at most 600 s",
        "  connection 3 bake 1: running, indirect 42.5%, 4 ranks",
        "  connection 5 bake 2: queued, waiting 0.0%",
        "memory budget: 256.0 MiB held, 768.0 MiB free of 1024.0 MiB",
        "mpi: launcher 'srun', up to 8 ranks a bake",
    };
    EXPECT_EQ(lines, expected);
}

TEST(ServerStatusPanel, ARefusalAndAnUnreachableServerAreOneLineEach) {
    EXPECT_EQ(server_panel_error_line("lan:7540", "the server refused: wrong token"),
              "server lan:7540: the server refused: wrong token");
    EXPECT_EQ(server_panel_error_line("lan:7540", "cannot connect to lan:7540: Connection refused"),
              "server lan:7540 unreachable: cannot connect to lan:7540: Connection refused");
}

// A loopback port that was free a moment ago: nothing listens there.
uint16_t closed_port() {
    asio::io_context io;
    tcp::acceptor acceptor(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    return acceptor.local_endpoint().port();
}

TEST(ServerStatusPanel, ThePollerReportsAServerNobodyAnswersFor) {
    ServerStatusQuery query;
    query.server = "127.0.0.1:" + std::to_string(closed_port());
    query.timeout_seconds = 2.0;
    ServerStatusPoller poller(query, std::chrono::milliseconds(50));
    EXPECT_EQ(poller.server(), query.server);
    while (poller.answers() < 2) std::this_thread::yield();  // it asks again after the interval
    const std::vector<std::string> lines = poller.lines();
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0].rfind("server " + query.server + " unreachable: cannot connect to ", 0), 0u)
        << lines[0];
}

}  // namespace
}  // namespace lc::client
