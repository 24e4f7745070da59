// SIGHUP and a crash keep nothing half-written: a real lightmass_server with a
// state directory (recordings, MPI job folders) and a 1,000,000-path VPL bake
// running. SIGHUP restarts it in place (same PID, the bake cancelled); SIGKILL
// then a new start sweeps what a crash left. Either way the state directory
// holds only complete files and the server serves again.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <thread>

#include "editor_client/bake/bake_client.h"
#include "editor_client/bake/server_process.h"
#include "editor_client/bake/server_status.h"
#include "protocol/asio.h"
#include "test_paths.h"
#include "tree_invariants.h"

namespace lc {
namespace {
namespace fs = std::filesystem;
using client::ServerProcess;
using namespace std::chrono_literals;

std::string bin(const std::string& program) {
    return (test::bin_dir() / program).string();
}

uint16_t free_port() {
    asio::io_context io;
    tcp::acceptor acceptor(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    return acceptor.local_endpoint().port();
}

// A PID no process has now: a child that has exited and been reaped.
pid_t dead_pid() {
    const pid_t child = fork();
    if (child == 0) _exit(0);
    waitpid(child, nullptr, 0);
    return child;
}

// Every entry under `dir` whose name marks a temporary (lightmass-bake-*, *.tmp-*).
std::vector<std::string> temporaries_under(const fs::path& dir) {
    std::vector<std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with("lightmass-bake-") || name.find(".tmp-") != std::string::npos)
            found.push_back(entry.path().string());
    }
    return found;
}

class ServerRestart : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::make_temp_dir("server-restart");
        state_ = dir_ / "state";
        fs::create_directories(state_ / "jobs");
        address_ = "127.0.0.1:" + std::to_string(free_port());
        const std::string scene = (dir_ / "room.gltf").string();
        ASSERT_EQ(
            std::system((bin("editor_client") + " make-scene room -o " + scene + " >/dev/null").c_str()), 0);
        ASSERT_EQ(std::system((bin("editor_client") + " add-lights " + scene +
                               " --count 24 --layout random --seed 5 --box -4.7,0.3,-4.7,4.7,2.7,4.7 -o " +
                               scene + " >/dev/null")
                                  .c_str()),
                  0);
    }
    void TearDown() override {
        if (baking_.joinable()) baking_.join();
        server_.reset();
        fs::remove_all(dir_);
    }
    void start_server() {
        auto server = ServerProcess::spawn_with(
            bin("lightmass_server"),
            {"--listen", address_, "--threads", "2", "--memory-budget-mb", "8192", "--record",
             (state_ / "recordings").string(), "--mpi-work-dir", (state_ / "jobs").string()});
        ASSERT_TRUE(server.ok()) << server.error();
        server_ = std::move(server.value());
    }
    // Starts a big bake in the background and returns once the server says it runs.
    void start_big_bake() {
        baking_ = std::thread([this] {
            const std::string command = bin("editor_client") + " bake " + (dir_ / "room.gltf").string() +
                                        " --server " + address_ +
                                        " --builder lbvh --indirect vpl --vpl-count 1000000 > " +
                                        (dir_ / "bake.log").string() + " 2>&1";
            bake_exit_ = std::system(command.c_str());
        });
        for (int attempt = 0; attempt < 1200 && !bake_running(); ++attempt) std::this_thread::sleep_for(50ms);
        ASSERT_TRUE(bake_running()) << test::read_text(dir_ / "bake.log");
    }
    Result<StatusReplyMsg> status() const {
        client::ServerStatusQuery query;
        query.server = address_;
        query.timeout_seconds = 5.0;
        return client::query_server_status(query);
    }
    bool bake_running() const {
        Result<StatusReplyMsg> now = status();
        return now && !now->bakes.empty() && now->bakes[0].state == "running";
    }
    // The status once the server answers again (it restarts, or starts), within about a minute.
    Result<StatusReplyMsg> status_once_serving() const {
        Result<StatusReplyMsg> answer = status();
        for (int attempt = 0; attempt < 600 && !answer; ++attempt) {
            std::this_thread::sleep_for(100ms);
            answer = status();
        }
        return answer;
    }
    void expect_it_bakes() const {
        client::BakeClientOptions options;
        options.server = address_;
        options.timeout_seconds = 60.0;
        auto baked =
            client::bake_lights(test::random_lights(40, 3, LightType::kPoint), Guid{9, 9, 9, 9}, options);
        ASSERT_TRUE(baked.ok()) << baked.error();
        EXPECT_EQ(baked->tree.nodes.size(), 79u);
    }

    fs::path dir_, state_;
    std::string address_;
    std::unique_ptr<ServerProcess> server_;
    std::thread baking_;
    int bake_exit_ = -1;
};

TEST_F(ServerRestart, SighupCancelsTheBakeAndRestartsInPlace) {
    start_server();
    start_big_bake();
    const pid_t pid = server_->pid();
    ASSERT_EQ(kill(pid, SIGHUP), 0);
    baking_.join();
    const std::string bake_log = test::read_text(dir_ / "bake.log");
    EXPECT_NE(bake_exit_, 0) << bake_log;
    EXPECT_NE(bake_log.find("bake 1 stopped: the server is restarting (SIGHUP)"), std::string::npos) << bake_log;

    Result<StatusReplyMsg> after = status_once_serving();
    ASSERT_TRUE(after.ok()) << after.error();
    EXPECT_TRUE(after->bakes.empty());
    EXPECT_EQ(kill(pid, 0), 0);  // the same process, run again
    EXPECT_EQ(temporaries_under(state_), std::vector<std::string>{});
    EXPECT_TRUE(fs::exists(state_ / "recordings"));  // the bake's scene channels, whole
    expect_it_bakes();
}

TEST_F(ServerRestart, AfterSigkillTheNextStartSweepsWhatWasLeft) {
    const pid_t dead = dead_pid();
    const std::string stale_job = "lightmass-bake-" + std::to_string(dead) + "-3";
    fs::create_directories(state_ / "jobs" / stale_job);
    std::ofstream(state_ / "jobs" / stale_job / "request.msg") << "half";
    std::ofstream(state_ / "jobs" / (stale_job + ".lcut")) << "half a tree";
    fs::create_directories(state_ / "recordings");
    const fs::path stale_dump = state_ / "recordings" / ("scene.dump.tmp-" + std::to_string(dead) + "-0");
    std::ofstream(stale_dump) << "half a dump";
    const fs::path living_job = state_ / "jobs" / ("lightmass-bake-" + std::to_string(getpid()) + "-1");
    fs::create_directories(living_job);  // another server's (this test's PID is alive): kept

    start_server();
    start_big_bake();
    ASSERT_EQ(kill(server_->pid(), SIGKILL), 0);
    server_.reset();  // reaps it
    baking_.join();
    EXPECT_NE(bake_exit_, 0);

    start_server();
    Result<StatusReplyMsg> after = status_once_serving();
    ASSERT_TRUE(after.ok()) << after.error();
    EXPECT_EQ(temporaries_under(state_), std::vector<std::string>{living_job.string()});
    expect_it_bakes();
}

}  // namespace
}  // namespace lc
