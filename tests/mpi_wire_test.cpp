// A bake over MPI ranks as the client sees it: a separately started
// lightmass_server and a raw peer bake the same lights in the server's
// process and over 2 and 3 ranks. The result channel's frames (OpenChannel,
// every WriteChannel, CloseChannel) are the same bytes, and BakeDone names the
// same tree: the coordinator streams rank 0's file as the tree in memory
// would be streamed. Skips, saying why, where mpirun or lightmass_rank is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "editor_client/bake/server_process.h"
#include "multi_rank_fixtures.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/codec.h"
#include "raw_client.h"
#include "test_paths.h"

namespace lc {
namespace {
namespace fs = std::filesystem;

const Guid kSceneGuid{3, 1, 4, 1};

bool mpirun_on_path() {
    const char* path = std::getenv("PATH");
    const std::string dirs = path ? path : "";
    for (size_t at = 0; at <= dirs.size();) {
        const size_t end = std::min(dirs.find(':', at), dirs.size());
        if (fs::exists(fs::path(dirs.substr(at, end - at)) / "mpirun")) return true;
        at = end + 1;
    }
    return false;
}

std::unique_ptr<client::ServerProcess> start_mpi_server() {
    const std::vector<std::string> args = {"--quiet",
                                           "--listen",
                                           "127.0.0.1:0",
                                           "--mpi-arg=--oversubscribe",
                                           "--mpi-arg=--allow-run-as-root",
                                           "--mpi-arg=--mca",
                                           "--mpi-arg=btl",
                                           "--mpi-arg=self,tcp",
                                           "--mpi-arg=--bind-to",
                                           "--mpi-arg=none",
                                           "--mpi-rank-program",
                                           (test::bin_dir() / "lightmass_rank").string()};
    auto server = client::ServerProcess::spawn_with((test::bin_dir() / "lightmass_server").string(), args);
    EXPECT_TRUE(server.ok()) << (server.ok() ? "" : server.error());
    return server.ok() ? std::move(server.value()) : nullptr;
}

struct WireResult {
    std::vector<std::vector<uint8_t>> channel_frames;  // OpenChannel, WriteChannel..., CloseChannel, encoded
    BakeDoneMsg done;
};

// One bake of `lights` on a fresh connection; the result channel's messages as encoded.
WireResult bake_over_the_wire(const client::ServerProcess& server, const std::vector<SceneLight>& lights,
                              uint32_t ranks) {
    WireResult result;
    test::RawClient peer(test::port_of(server.address()), std::chrono::seconds(120));
    EXPECT_TRUE(peer.send(HelloMsg{kProtocolVersion, "mpi wire test", ""}));
    EXPECT_TRUE(peer.receive().has_value());
    const std::vector<uint8_t> scene = encode_scene_channel(lights);
    EXPECT_TRUE(peer.send(OpenChannelMsg{1, scene_channel_name(kSceneGuid), scene.size()}));
    EXPECT_TRUE(peer.send(WriteChannelMsg{1, 0, scene}));
    EXPECT_TRUE(peer.send(CloseChannelMsg{1}));
    BakeRequestMsg request;
    request.bake_id = 7;
    request.scene_channel = scene_channel_name(kSceneGuid);
    request.builder = BuilderKind::kLbvh;
    request.seed = 3;
    request.ranks = ranks;
    EXPECT_TRUE(peer.send(request));
    while (std::optional<Message> message = peer.receive()) {
        if (auto* error = std::get_if<ErrorMsg>(&*message)) {
            ADD_FAILURE() << ranks << " ranks: " << error->text;
            break;
        }
        if (auto* done = std::get_if<BakeDoneMsg>(&*message)) {
            result.done = *done;
            return result;
        }
        const bool channel = std::holds_alternative<OpenChannelMsg>(*message) ||
                             std::holds_alternative<WriteChannelMsg>(*message) ||
                             std::holds_alternative<CloseChannelMsg>(*message);
        if (channel) result.channel_frames.push_back(encode_message(*message));
    }
    ADD_FAILURE() << ranks << " ranks: no BakeDone";
    return result;
}

TEST(MpiWire, TheResultChannelIsTheSameBytesOverRanksAsInTheServersProcess) {
    if (!mpirun_on_path()) GTEST_SKIP() << "mpirun is not on PATH (apt-get install openmpi-bin)";
    if (!fs::exists(test::bin_dir() / "lightmass_rank"))
        GTEST_SKIP() << "lightmass_rank was not built (CMake found no MPI: libopenmpi-dev)";
    auto server = start_mpi_server();
    ASSERT_TRUE(server);
    const std::vector<SceneLight> lights = test::scattered_lights(30000);
    const WireResult in_process = bake_over_the_wire(*server, lights, 0);
    ASSERT_GE(in_process.channel_frames.size(), 4u) << "open, two chunks or more, close";
    EXPECT_EQ(in_process.done.leaf_count, lights.size());
    for (uint32_t ranks : {2u, 3u}) {
        const WireResult over_ranks = bake_over_the_wire(*server, lights, ranks);
        EXPECT_EQ(over_ranks.channel_frames, in_process.channel_frames) << ranks << " ranks";
        EXPECT_EQ(over_ranks.done.result_channel, in_process.done.result_channel);
        EXPECT_EQ(over_ranks.done.node_count, in_process.done.node_count) << ranks << " ranks";
        EXPECT_EQ(over_ranks.done.leaf_count, in_process.done.leaf_count) << ranks << " ranks";
        // The ranks did bake it: rank 0 reports a line for the last rank.
        const std::string last_rank = "rank " + std::to_string(ranks - 1) + " lights ";
        EXPECT_TRUE(std::any_of(over_ranks.done.effects.begin(), over_ranks.done.effects.end(),
                                [&](const std::string& effect) { return effect.rfind(last_rank, 0) == 0; }))
            << ranks << " ranks: no '" << last_rank << "...' in BakeDone's effects";
    }
}

}  // namespace
}  // namespace lc
