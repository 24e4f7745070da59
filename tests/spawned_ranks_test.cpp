// `editor_client bake --spawn-server --ranks N` as a user runs it on a small
// machine: the client hands the server it starts its MPI settings, a local
// launch with more ranks than cores oversubscribes and says so, the tree's
// bytes are one rank's, and a refusal reaches the user as one line naming the
// flag that fixes it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "test_paths.h"

namespace lc::client {
namespace {
namespace fs = std::filesystem;

struct BakeRun {
    int exit_code = -1;
    std::string output;  // stdout and stderr
};

class SpawnedRanks : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::system("command -v mpirun > /dev/null 2>&1") != 0)
            GTEST_SKIP() << "mpirun is not on PATH (apt-get install openmpi-bin)";
        if (!fs::exists(test::bin_dir() / "lightmass_rank"))
            GTEST_SKIP() << "lightmass_rank was not built (CMake found no MPI: libopenmpi-dev)";
        dir_ = test::make_temp_dir("spawned-ranks");
        Scene scene = make_room_scene();
        LightLayoutOptions layout;
        layout.count = 24;
        layout.seed = 5;
        layout.box_min = kRoomLightBoxMin;
        layout.box_max = kRoomLightBoxMax;
        Result<std::vector<SceneLight>> lights = generate_lights(layout);
        ASSERT_TRUE(lights.ok()) << lights.error();
        scene.lights = *lights;
        scene_ = dir_ / "room.gltf";
        ASSERT_TRUE(write_scene_gltf(scene, scene_).ok());
    }
    void TearDown() override {
        if (!dir_.empty()) fs::remove_all(dir_);
    }

    // The bake's own flags after the scene; as root (a CI container) Open MPI needs its consent.
    BakeRun bake(const std::string& flags) const {
        const std::string root = geteuid() == 0 ? " --server-arg=--mpi-arg=--allow-run-as-root" : "";
        const fs::path log = dir_ / "bake.log";
        const std::string command = (test::bin_dir() / "editor_client").string() + " bake " + scene_.string() +
                                    " --spawn-server --builder lbvh --indirect vpl --vpl-count 2000 " + flags +
                                    root + " > " + log.string() + " 2>&1";
        const int status = std::system(command.c_str());
        return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::read_text(log)};
    }

    fs::path dir_, scene_;
};

TEST_F(SpawnedRanks, ThreeRanksBakeOneRanksBytesAndTheSummaryCountsTheTreesLights) {
    const BakeRun one = bake("--ranks 1 -o " + (dir_ / "one.lcut").string());
    ASSERT_EQ(one.exit_code, 0) << one.output;
    const BakeRun three = bake("--ranks 3 -o " + (dir_ / "three.lcut").string());
    ASSERT_EQ(three.exit_code, 0) << three.output;
    const std::string one_bytes = test::read_text(dir_ / "one.lcut");
    ASSERT_FALSE(one_bytes.empty());
    EXPECT_TRUE(one_bytes == test::read_text(dir_ / "three.lcut")) << "3 ranks baked other bytes than 1";
    // "baked N lights (24 punctual, V VPLs; 0 classic kept local) into 2N-1 nodes"
    const size_t at = three.output.find("baked ");
    ASSERT_NE(at, std::string::npos) << three.output;
    const unsigned long leaves = std::stoul(three.output.substr(at + 6));
    EXPECT_GT(leaves, 24u);
    const std::string vpls = std::to_string(leaves - 24) + " VPLs";
    EXPECT_NE(three.output.find("lights (24 punctual, " + vpls + "; 0 classic kept local) into " +
                                std::to_string(2 * leaves - 1) + " nodes"),
              std::string::npos)
        << three.output;
    if (std::thread::hardware_concurrency() < 3) {
        EXPECT_NE(three.output.find("mpi: 3 ranks on this machine's "), std::string::npos) << three.output;
    }
}

TEST_F(SpawnedRanks, TooFewSlotsIsOneLineNamingTheFlag) {
    const unsigned ranks = std::max(2u, std::thread::hardware_concurrency() + 1);
    const BakeRun refused = bake("--ranks " + std::to_string(ranks) + " --server-arg=--mpi-oversubscribe=off");
    EXPECT_NE(refused.exit_code, 0) << refused.output;
    const std::string expected = "bake 1 failed: MPI: mpirun found fewer slots than the " +
                                 std::to_string(ranks) + " ranks asked for: pass lightmass_server "
                                 "--mpi-oversubscribe on";
    EXPECT_NE(refused.output.find(expected), std::string::npos) << refused.output;
    EXPECT_EQ(refused.output.find("There are not enough slots"), std::string::npos)
        << "Open MPI's own box reached the user:\n" << refused.output;
}

}  // namespace
}  // namespace lc::client
