// The rows of issue 27 against a real lightmass_server: a peer silent with a
// channel open, a bake past --max-bake-seconds, SIGTERM during a radiosity
// bake's point-light pass, and a small bake sent while a 10^9-path one runs.
// Bounds here are generous (seconds, where the old server never ended);
// latencies are measured by scripts/fault_test.sh hostile-bake.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "editor_client/bake/bake_client.h"
#include "editor_client/bake/server_process.h"
#include "indirect_scenes.h"
#include "protocol/channel_name.h"
#include "raw_client.h"
#include "test_paths.h"
#include "tree_invariants.h"

namespace lc {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
constexpr Guid kSceneGuid{0x27272727u, 0x1u, 0x2u, 0x3u};

std::unique_ptr<client::ServerProcess> start_server(std::vector<std::string> extra) {
    std::vector<std::string> args = {"--quiet", "--listen", "127.0.0.1:0"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto server = client::ServerProcess::spawn_with((test::bin_dir() / "lightmass_server").string(), args);
    EXPECT_TRUE(server.ok()) << (server.ok() ? "" : server.error());
    return server.ok() ? std::move(server.value()) : nullptr;
}

// A black closed box of side 4 around the lights: every ray hits a wall, no
// light is reflected, so a bake's time goes into rays, not into memory.
client::BakeClientOptions furnace_bake(const client::ServerProcess& server, IndirectRequest indirect) {
    client::BakeClientOptions options;
    options.server = server.address();
    options.timeout_seconds = 120.0;
    options.geometry =
        std::make_shared<const SceneGeometry>(test::closed_box({glm::vec3(0.0f), glm::vec3(0.0f)}, 4.0f));
    options.indirect = indirect;
    return options;
}

std::vector<SceneLight> point_lights(uint32_t count) {
    return test::random_lights(count, 9, LightType::kPoint, 4.0f);
}

// A bake on its own thread that says when its server reports a stage past the queue.
struct BackgroundBake {
    std::atomic<bool> started{false};
    std::atomic<bool> finished{false};
    std::atomic<bool> cancel{false};
    client::BakeWaker waker;
    Result<client::BakeOutcome> outcome = make_error("not run");
    std::thread thread;

    BackgroundBake(std::vector<SceneLight> lights, client::BakeClientOptions options) {
        options.on_progress = [this](const ProgressMsg& progress) {
            if (progress.stage != "queued") started = true;
        };
        options.cancel = &cancel;
        options.waker = &waker;
        thread = std::thread([this, lights = std::move(lights), options] {
            outcome = client::bake_lights(lights, kSceneGuid, options);
            finished = true;
        });
    }
    ~BackgroundBake() {
        if (thread.joinable()) thread.join();
    }
    bool wait_started() {
        const auto until = Clock::now() + 30s;
        while (!started && !finished && Clock::now() < until) std::this_thread::sleep_for(10ms);
        return started && !finished;
    }
};

TEST(HostileBake, APeerSilentWithAChannelOpenIsClosedAndItsBytesFreed) {
    auto server = start_server(
        {"--read-timeout-ms", "500", "--idle-timeout-ms", "600000", "--memory-budget-mb", "512"});
    ASSERT_TRUE(server);
    const uint64_t announced = uint64_t{200} << 20;  // within the 256 MB a connection may hold
    test::RawClient silent(test::port_of(server->address()), 10s);
    ASSERT_TRUE(silent.send(HelloMsg{kProtocolVersion, "silent", ""}));
    ASSERT_TRUE(silent.receive().has_value());
    ASSERT_TRUE(silent.send(OpenChannelMsg{1, scene_channel_name(kSceneGuid), announced}));
    ASSERT_TRUE(silent.send(WriteChannelMsg{1, 0, std::vector<uint8_t>(2, 0)}));
    // Whole frames only: no partial frame holds the old read deadline. The idle
    // timeout (10 minutes) would leave this peer connected, its 200 MB reserved.
    const auto start = Clock::now();
    EXPECT_TRUE(silent.wait_closed());
    EXPECT_LT(Clock::now() - start, 5s);
    // Its reservation is back: another peer may hold a 200 MB channel now.
    test::RawClient next(test::port_of(server->address()), 10s);
    ASSERT_TRUE(next.send(HelloMsg{kProtocolVersion, "next", ""}));
    ASSERT_TRUE(next.receive().has_value());
    ASSERT_TRUE(next.send(OpenChannelMsg{1, scene_channel_name(kSceneGuid), announced}));
    ASSERT_TRUE(next.send(OpenChannelMsg{2, scene_channel_name(kSceneGuid), announced}));
    // The second is over this connection's cap (half the budget): busy, and only it.
    auto reply = next.receive();
    ASSERT_TRUE(reply.has_value());
    auto* error = std::get_if<ErrorMsg>(&*reply);
    ASSERT_NE(error, nullptr);
    EXPECT_EQ(error->code, ErrorCode::kBusy);
    EXPECT_NE(error->text.find("channel '"), std::string::npos) << error->text;
}

TEST(HostileBake, ARunawayBakeEndsAtItsDeadlineWithAnErrorSayingSo) {
    auto server = start_server({"--max-bake-seconds", "1"});
    ASSERT_TRUE(server);
    auto options = furnace_bake(*server, {IndirectMethod::kVpl, 1, uint64_t{1} << 30, 0.25f, 0.01f});
    auto outcome = client::bake_lights(point_lights(4), kSceneGuid, options);
    ASSERT_FALSE(outcome.ok());
    EXPECT_NE(outcome.error().find("ran past --max-bake-seconds 1"), std::string::npos) << outcome.error();
}

TEST(HostileBake, SigtermStopsARadiosityBakeInItsPointLightPass) {
    auto server = start_server({"--threads", "1"});
    ASSERT_TRUE(server);
    // 1,000 point lights over about 150,000 patches: minutes of shadow rays.
    BackgroundBake bake(point_lights(1000),
                        furnace_bake(*server, {IndirectMethod::kRadiosity, 1, 1, 0.05f, 0.01f}));
    ASSERT_TRUE(bake.wait_started());
    std::this_thread::sleep_for(300ms);  // inside the point-light pass
    EXPECT_EQ(server->terminate(), 0) << "the server did not exit within 5 s of SIGTERM";
    bake.thread.join();
    EXPECT_FALSE(bake.outcome.ok());
}

TEST(HostileBake, ASmallBakeIsNotStuckBehindAHugeOne) {
    auto server = start_server({"--threads", "1"});
    ASSERT_TRUE(server);
    BackgroundBake huge(point_lights(4),
                        furnace_bake(*server, {IndirectMethod::kVpl, 1, 1000000000, 0.25f, 0.01f}));
    ASSERT_TRUE(huge.wait_started());
    client::BakeClientOptions small;
    small.server = server->address();
    auto outcome = client::bake_lights(point_lights(20), kSceneGuid, small);
    ASSERT_TRUE(outcome.ok()) << outcome.error();
    EXPECT_EQ(outcome->tree.leaf_count, 20u);
    EXPECT_FALSE(huge.finished) << "the huge bake ended before the small one";
    huge.cancel = true;
    huge.waker.wake();
    huge.thread.join();
    ASSERT_FALSE(huge.outcome.ok());
    EXPECT_EQ(huge.outcome.error_kind(), ErrorKind::kCancelled) << huge.outcome.error();
}

}  // namespace
}  // namespace lc
