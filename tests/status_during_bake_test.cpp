// A status request never waits on bake work: with a bake held on its lane
// thread (the server's test hook), a StatusRequest is still answered and shows
// the bake, and the held thread runs at the server's --bake-nice level.
#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <algorithm>
#include <thread>

#include "editor_client/bake/bake_client.h"
#include "editor_client/bake/server_status.h"
#include "lightmass_server/control/bake_priority.h"
#include "lightmass_server/net/server.h"
#include "tree_invariants.h"

namespace lc {
namespace {

constexpr Guid kSceneGuid{0x5a7u, 0x1u, 0x2u, 0x3u};

// A gate the bake thread waits at until the test opens it.
class Gate {
public:
    void arrive_and_wait(int nice) {
        std::unique_lock lock(mutex_);
        arrived_ = true;
        nice_seen_ = nice;
        changed_.notify_all();
        changed_.wait(lock, [&] { return open_; });
    }
    int wait_for_arrival() {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return arrived_; });
        return nice_seen_;
    }
    void open() {
        std::lock_guard lock(mutex_);
        open_ = true;
        changed_.notify_all();
    }

private:
    std::mutex mutex_;
    std::condition_variable changed_;
    bool arrived_ = false, open_ = false;
    int nice_seen_ = 0;
};

TEST(StatusDuringBake, AnsweredWhileABakeHoldsTheWorker) {
    Gate gate;
    bake::ServerOptions options;
    options.max_concurrent_bakes = 1;
    options.bake_nice = 7;
    options.on_bake_thread_start = [&] { gate.arrive_and_wait(bake::this_thread_nice()); };
    bake::Server server(options);
    Result<tcp::endpoint> endpoint = server.listen();
    ASSERT_TRUE(endpoint.ok()) << endpoint.error();
    std::thread serving([&] { server.run(); });
    const std::string address = "127.0.0.1:" + std::to_string(endpoint->port());

    Result<client::BakeOutcome> outcome = make_error("not run");
    std::thread baking([&] {
        client::BakeClientOptions bake_options;
        bake_options.server = address;
        bake_options.timeout_seconds = 60.0;
        outcome =
            client::bake_lights(test::random_lights(40, 3, LightType::kPoint), kSceneGuid, bake_options);
    });
    const int held_nice = gate.wait_for_arrival();

    client::ServerStatusQuery query;
    query.server = address;
    Result<StatusReplyMsg> status = client::query_server_status(query);
    gate.open();
    baking.join();
    server.stop();
    serving.join();

    ASSERT_TRUE(status.ok()) << status.error();
    ASSERT_EQ(status->bakes.size(), 1u);
    EXPECT_EQ(status->bakes[0].state, "queued");  // held before its first progress
    EXPECT_EQ(status->connections, 2u);           // the baking one and the asking one
    EXPECT_GE(held_nice, 7);
    ASSERT_TRUE(outcome.ok()) << outcome.error();
    EXPECT_EQ(outcome->tree.nodes.size(), 79u);  // 40 lights: 2n - 1 nodes
}

TEST(StatusDuringBake, LoweringAThreadsPriorityNeverRaisesIt) {
    std::thread([] {
        // The test itself may run niced (`nice ctest`): lowering to 5 keeps whichever is lower.
        const int start = bake::this_thread_nice();
        const int lowered = std::max(start, 5);
        ASSERT_TRUE(bake::lower_this_thread_priority(5));
        EXPECT_EQ(bake::this_thread_nice(), lowered);
        ASSERT_TRUE(bake::lower_this_thread_priority(3));  // already lower: kept
        EXPECT_EQ(bake::this_thread_nice(), lowered);
    }).join();
}

}  // namespace
}  // namespace lc
