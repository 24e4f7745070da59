// The server's limits over real sockets (issue 14): back-off when accept runs
// out of file descriptors, a deadline for a whole frame, a handshake deadline
// on both sides, and a cap on connections and memory answered with "busy".
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>
#include <vector>

#include <unistd.h>

#include "editor_client/bake/bake_client.h"
#include "editor_client/bake/server_process.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "raw_client.h"
#include "test_paths.h"
#include "tree_invariants.h"

namespace lc {
namespace {

using namespace std::chrono_literals;
using client::ServerProcess;
using Clock = std::chrono::steady_clock;

constexpr Guid kSceneGuid{0x51515151u, 0x2u, 0x3u, 0x4u};

std::string server_binary() { return (test::bin_dir() / "lightmass_server").string(); }

std::unique_ptr<ServerProcess> start_server(std::vector<std::string> extra, const std::string& launcher = "") {
    std::vector<std::string> args;
    std::string binary = server_binary();
    if (!launcher.empty()) {  // prlimit: the same process, with other limits
        args = {"--nofile=64", binary};
        binary = launcher;
    }
    for (const char* arg : {"--quiet", "--listen", "127.0.0.1:0"}) args.push_back(arg);
    args.insert(args.end(), extra.begin(), extra.end());
    auto server = ServerProcess::spawn_with(binary, args);
    EXPECT_TRUE(server.ok()) << (server.ok() ? "" : server.error());
    return server.ok() ? std::move(server.value()) : nullptr;
}

client::BakeClientOptions options_for(const ServerProcess& server) {
    client::BakeClientOptions options;
    options.server = server.address();
    options.timeout_seconds = 60.0;
    return options;
}

std::vector<SceneLight> lights(uint32_t count) { return test::random_lights(count, 5, LightType::kPoint); }

// CPU seconds (user + system) the process has used so far.
double cpu_seconds(pid_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::istringstream fields(text.substr(text.rfind(')') + 2));
    std::string field;
    unsigned long long utime = 0, stime = 0;
    for (int i = 3; i <= 15 && fields >> field; ++i) {
        if (i == 14) utime = std::stoull(field);
        if (i == 15) stime = std::stoull(field);
    }
    return double(utime + stime) / double(::sysconf(_SC_CLK_TCK));
}

// Threads the process has now (/proc/PID/task holds one entry per thread).
size_t thread_count(pid_t pid) {
    const std::filesystem::path tasks = "/proc/" + std::to_string(pid) + "/task";
    return size_t(
        std::distance(std::filesystem::directory_iterator(tasks), std::filesystem::directory_iterator{}));
}

TEST(ServerLimits, OneBakeThreadIsOneThreadForTheBuildersToo) {
    auto server = start_server({"--threads", "1"});
    ASSERT_TRUE(server);
    const size_t idle = thread_count(server->pid());  // the I/O thread and the one bake worker
    client::BakeClientOptions options = options_for(*server);
    options.builder = BuilderKind::kAgglomerative;  // parallel loops over many TBB tasks
    auto outcome = client::bake_lights(lights(40000), kSceneGuid, options);
    ASSERT_TRUE(outcome.ok()) << outcome.error();
    // TBB keeps the workers it started asleep in the process: none may appear.
    EXPECT_EQ(thread_count(server->pid()), idle);
}

TEST(ServerLimits, OutOfFileDescriptorsBacksOffAndRecovers) {
    if (::access("/usr/bin/prlimit", X_OK) != 0) GTEST_SKIP() << "prlimit (util-linux) is not installed";
#if defined(__SANITIZE_ADDRESS__)
    // The sanitizers probe memory through a pipe, which a process without a
    // free descriptor cannot open: UBSan then reports every virtual call as an
    // invalid vptr (seen in fmt) and stops the server. Not a finding of ours.
    GTEST_SKIP() << "a sanitizer build cannot run out of file descriptors (its memory probes need one)";
#endif
    auto server = start_server({"--idle-timeout-ms", "600000"}, "/usr/bin/prlimit");
    ASSERT_TRUE(server);
    // 100 idle connections against 64 descriptors: accept fails with EMFILE
    // while the rest wait in the backlog.
    std::vector<std::unique_ptr<test::RawClient>> idle;
    for (int i = 0; i < 100; ++i)
        idle.push_back(std::make_unique<test::RawClient>(test::port_of(server->address()), 1s));
    std::this_thread::sleep_for(300ms);
    const double before = cpu_seconds(server->pid());
    std::this_thread::sleep_for(2s);
    const double used = cpu_seconds(server->pid()) - before;
    // Retrying at once spun here 0.48 CPU seconds in these 2 s, writing 525,197 log lines.
    EXPECT_LT(used, 0.1) << "CPU seconds in two seconds of failing accepts";

    idle.clear();
    auto outcome = client::bake_lights(lights(20), kSceneGuid, options_for(*server));
    ASSERT_TRUE(outcome.ok()) << outcome.error();
    EXPECT_EQ(outcome->tree.leaf_count, 20u);
}

TEST(ServerLimits, FrameTricklingInIsDroppedAtTheFrameDeadline) {
    auto server = start_server({"--read-timeout-ms", "800", "--frame-timeout-ms", "1000",
                                "--connect-timeout-ms", "60000"});
    ASSERT_TRUE(server);
    test::RawClient peer(test::port_of(server->address()));
    const std::vector<uint8_t> header = {0xFF, 0xFF, 0xFF, 0x00};  // 16 MiB - 1
    ASSERT_TRUE(peer.send_bytes(header));
    const auto start = Clock::now();
    bool closed = false;
    // One byte every 200 ms: never quiet for the read timeout. Once the server
    // has closed, a send is answered with a reset and the next one fails.
    while (!closed && Clock::now() - start < 6s) {
        std::this_thread::sleep_for(200ms);
        const std::vector<uint8_t> one = {0x00};
        closed = !peer.send_bytes(one);
    }
    const auto elapsed = Clock::now() - start;
    EXPECT_TRUE(closed);
    EXPECT_LT(elapsed, 3s);
    EXPECT_GE(elapsed, 900ms);
}

TEST(ServerLimits, ServerDropsAPeerThatNeverSaysHello) {
    auto server = start_server({"--connect-timeout-ms", "300"});
    ASSERT_TRUE(server);
    test::RawClient peer(test::port_of(server->address()), 5s);
    const auto start = Clock::now();
    EXPECT_TRUE(peer.wait_closed());
    EXPECT_LT(Clock::now() - start, 3s);
}

TEST(ServerLimits, ClientGivesUpOnAServerThatNeverAnswersHello) {
    asio::io_context io;
    tcp::acceptor mute(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    client::BakeClientOptions options;
    options.server = "127.0.0.1:" + std::to_string(mute.local_endpoint().port());
    options.connect_timeout_seconds = 0.5;
    const auto start = Clock::now();
    auto outcome = client::bake_lights(lights(5), kSceneGuid, options);  // the backlog accepts it
    ASSERT_FALSE(outcome.ok());
    EXPECT_LT(Clock::now() - start, 5s);
    EXPECT_NE(outcome.error().find("did not answer Hello"), std::string::npos) << outcome.error();
}

TEST(ServerLimits, ConnectionsAboveTheLimitAreBusy) {
    auto server = start_server({"--max-connections", "2"});
    ASSERT_TRUE(server);
    std::vector<std::unique_ptr<test::RawClient>> held;
    for (int i = 0; i < 2; ++i) {
        held.push_back(std::make_unique<test::RawClient>(test::port_of(server->address())));
        ASSERT_TRUE(held.back()->send(HelloMsg{kProtocolVersion, "holder", ""}));
        auto ack = held.back()->receive();
        ASSERT_TRUE(ack && std::holds_alternative<HelloAckMsg>(*ack));
    }
    auto refused = client::bake_lights(lights(5), kSceneGuid, options_for(*server));
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error_kind(), ErrorKind::kBusy) << refused.error();

    held.clear();  // the slots free up as the server sees the peers leave
    Result<client::BakeOutcome> later = make_error("not tried");
    for (int i = 0; i < 50 && !later.ok(); ++i) {
        std::this_thread::sleep_for(20ms);
        later = client::bake_lights(lights(5), kSceneGuid, options_for(*server));
    }
    EXPECT_TRUE(later.ok()) << later.error();
}

TEST(ServerLimits, ChannelsAboveTheMemoryBudgetAreBusy) {
    // Room for a small bake (bake_footprint.h: 20 MiB a bake and its lights), not for a 32 MiB channel.
    auto server = start_server({"--memory-budget-mb", "24"});
    ASSERT_TRUE(server);
    test::RawClient peer(test::port_of(server->address()));
    ASSERT_TRUE(peer.send(HelloMsg{kProtocolVersion, "test", ""}));
    ASSERT_TRUE(peer.receive().has_value());
    ASSERT_TRUE(peer.send(OpenChannelMsg{1, scene_channel_name(kSceneGuid), 32u << 20}));
    auto reply = peer.receive();
    ASSERT_TRUE(reply.has_value());
    auto* error = std::get_if<ErrorMsg>(&*reply);
    ASSERT_NE(error, nullptr);
    EXPECT_EQ(error->code, ErrorCode::kBusy) << error->text;
    // Within the budget the same connection still bakes.
    auto outcome = client::bake_lights(lights(50), kSceneGuid, options_for(*server));
    EXPECT_TRUE(outcome.ok()) << outcome.error();
}

}  // namespace
}  // namespace lc
