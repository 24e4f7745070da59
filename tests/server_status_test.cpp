// Status over the wire, on a real server over a socket: `editor_client
// server-status` (and query_server_status under it) answers with the server's
// version, budget, limits and MPI settings, as text and as JSON, and a server
// with a token refuses a client without it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <string>

#include "editor_client/bake/server_process.h"
#include "editor_client/bake/server_status.h"
#include "lightcuts/version.h"
#include "test_paths.h"

namespace lc::client {
namespace {
namespace fs = std::filesystem;

struct CommandRun {
    int exit_code = -1;
    std::string output;
};

class ServerStatus : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::make_temp_dir("server-status");
        token_ = dir_ / "token";
        std::ofstream(token_) << "status-secret-0123456789\n";
        Result<std::unique_ptr<ServerProcess>> server = ServerProcess::spawn_with(
            (test::bin_dir() / "lightmass_server").string(),
            {"--listen", "127.0.0.1:0", "--token-file", token_.string(), "--memory-budget-mb", "512",
             "--max-connections", "9", "--max-bake-seconds", "77", "--mpi-max-ranks", "4", "--quiet"});
        ASSERT_TRUE(server.ok()) << server.error();
        server_ = std::move(server.value());
    }
    void TearDown() override {
        server_.reset();
        fs::remove_all(dir_);
    }
    CommandRun server_status(const std::string& flags) const {
        const fs::path log = dir_ / "status.log";
        const std::string command = (test::bin_dir() / "editor_client").string() + " server-status " +
                                    server_->address() + " " + flags + " > " + log.string() + " 2>&1";
        const int status = std::system(command.c_str());
        return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::read_text(log)};
    }

    fs::path dir_, token_;
    std::unique_ptr<ServerProcess> server_;
};

TEST_F(ServerStatus, TheReplyHoldsTheServersVersionBudgetLimitsAndMpi) {
    ServerStatusQuery query;
    query.server = server_->address();
    query.token_file = token_;
    Result<StatusReplyMsg> status = query_server_status(query);
    ASSERT_TRUE(status.ok()) << status.error();
    EXPECT_EQ(status->version, std::string("lightmass_server ") + kVersion);
    EXPECT_GE(status->uptime_seconds, 0.0);
    EXPECT_EQ(status->connections, 1u);  // the asking one
    EXPECT_TRUE(status->bakes.empty());
    EXPECT_EQ(status->memory_budget_bytes, uint64_t{512} << 20);
    EXPECT_EQ(status->memory_held_bytes, 0u);
    EXPECT_EQ(status->max_connections, 9u);
    EXPECT_EQ(status->max_bake_seconds, 77u);
    EXPECT_GE(status->max_concurrent_bakes, 1u);
    EXPECT_EQ(status->mpi_launcher, "mpirun");
    EXPECT_EQ(status->mpi_max_ranks, 4u);
}

TEST_F(ServerStatus, TheCommandPrintsTextAndJson) {
    const CommandRun text = server_status("--token-file " + token_.string());
    ASSERT_EQ(text.exit_code, 0) << text.output;
    EXPECT_EQ(text.output.rfind(std::string("lightmass_server ") + kVersion + ", up ", 0), 0u) << text.output;
    EXPECT_NE(text.output.find("bakes: 0 running, 0 queued, 0 streaming"), std::string::npos) << text.output;
    EXPECT_NE(text.output.find("memory budget: 0.0 MiB held, 512.0 MiB free of 512.0 MiB"), std::string::npos)
        << text.output;
    EXPECT_NE(text.output.find("mpi: launcher 'mpirun', up to 4 ranks a bake"), std::string::npos) << text.output;

    const CommandRun json = server_status("--json --token-file " + token_.string());
    ASSERT_EQ(json.exit_code, 0) << json.output;
    const nlohmann::json j = nlohmann::json::parse(json.output);
    EXPECT_EQ(j["memory_free_bytes"], uint64_t{512} << 20);
    EXPECT_EQ(j["bakes_running"], 0);
    EXPECT_EQ(j["limits"]["max_connections"], 9);
    EXPECT_EQ(j["mpi"]["max_ranks"], 4);
}

TEST_F(ServerStatus, WithoutTheTokenTheServerRefuses) {
    const CommandRun refused = server_status("");
    EXPECT_NE(refused.exit_code, 0) << refused.output;
    EXPECT_NE(refused.output.find("server-status: the server refused: "), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find("token"), std::string::npos) << refused.output;
}

}  // namespace
}  // namespace lc::client
