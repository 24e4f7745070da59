// Bakes over MPI ranks (lightmass_server/mpi/): the light set and the tree the
// same at 1, 2, 3 and 4 ranks as in one process (VPLs, area and sky samples,
// radiosity split over the ranks' receiver patches), the LBVH built and written
// over the ranks (split_lbvh.h: each rank's records at their indices, a valid
// result channel, uneven shares), a rank that dies, a cancelled bake, the bake's
// own stop (a deadline, a cancel) and a bake asking for more ranks than the
// server allows. The tests that start mpirun skip, saying why, where mpirun or
// lightmass_rank is missing (the shares' determinism and the tree written in
// parts are checked without MPI in index_shares_test and lbvh_subtrees_test).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

#include "lightmass_server/bake/result_channel_file.h"
#include "lightmass_server/indirect/vpl_tracer.h"
#include "lightmass_server/mpi/bake_dispatch.h"
#include "lightmass_server/mpi/host_roster.h"
#include "multi_rank_fixtures.h"
#include "protocol/channel_records.h"

namespace lc::bake {
namespace {
namespace fs = std::filesystem;
using test::cornell_inputs;
using test::scattered_lights;

const fs::path kRankProgram = fs::path(LC_BIN_DIR) / "lightmass_rank";

bool on_path(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "";
    for (size_t at = 0; at <= dirs.size();) {
        const size_t end = std::min(dirs.find(':', at), dirs.size());
        if (fs::exists(fs::path(dirs.substr(at, end - at)) / program)) return true;
        at = end + 1;
    }
    return false;
}

#define SKIP_WITHOUT_MPI()                                                                             \
    do {                                                                                               \
        if (!on_path("mpirun")) GTEST_SKIP() << "mpirun is not on PATH (apt-get install openmpi-bin)"; \
        if (!fs::exists(kRankProgram))                                                                 \
            GTEST_SKIP() << kRankProgram << " was not built (CMake found no MPI: libopenmpi-dev)";     \
    } while (0)

size_t processes_naming(const std::string& needle);

// The result channel's bytes: encoded from the tree, or read from the file a
// bake over ranks leaves it in (streamed from there to the client as is).
std::vector<uint8_t> tree_bytes(const Result<BuildResult>& built) {
    EXPECT_TRUE(built.ok()) << (built ? "" : built.error());
    if (!built) return {};
    if (!built->channel_file) return encode_result_channel(built->tree);
    EXPECT_TRUE(built->tree.nodes.empty()) << "a bake over ranks decoded its tree in the coordinator";
    std::vector<uint8_t> bytes(built->channel_file->size_bytes());
    Status read = built->channel_file->read(0, bytes);
    EXPECT_TRUE(read.ok()) << (read ? "" : read.error());
    return bytes;
}

TEST(MpiBake, TheLbvhTreeIsTheSameWhenTheRanksMergeItsSubtrees) {
    SKIP_WITHOUT_MPI();
    BakeInputs inputs = cornell_inputs();
    inputs.lights = std::make_shared<std::vector<SceneLight>>(scattered_lights(20000));
    const std::vector<uint8_t> in_process = tree_bytes(run_bake(inputs, {}));
    for (uint32_t ranks : {2u, 4u}) {
        inputs.ranks = ranks;
        Result<BuildResult> built = run_bake(inputs, {});
        EXPECT_EQ(tree_bytes(built), in_process) << ranks << " ranks";
        // Every rank but 0 sent lights to the rank that owns their part of space (split_lbvh.h).
        for (const std::string& effect : built ? built->report.effects : std::vector<std::string>{}) {
            if (effect.rfind("rank ", 0) == 0 && effect.rfind("rank 0 ", 0) != 0) {
                EXPECT_EQ(effect.find("bytes_sent 0 "), std::string::npos) << effect;
            }
        }
    }
}

// Scene lights only, no geometry: the tree is built over the ranks from rank 0's lights alone.
BakeInputs lights_only(std::vector<SceneLight> lights) {
    BakeInputs inputs = cornell_inputs();
    inputs.lights = std::make_shared<std::vector<SceneLight>>(std::move(lights));
    inputs.geometry = nullptr;
    inputs.environment = nullptr;
    inputs.indirect.method = IndirectMethod::kOff;
    return inputs;
}

// The records each rank wrote form a valid result channel (the coordinator
// checked it when it adopted the file; decoding checks it again) of `lights` leaves.
void expect_valid_tree(const std::vector<uint8_t>& bytes, size_t lights, uint32_t ranks) {
    Result<LightTree> tree = decode_result_channel(bytes);
    ASSERT_TRUE(tree.ok()) << ranks << " ranks: " << tree.error();
    EXPECT_EQ(tree->leaf_count, lights) << ranks << " ranks";
}

// Shares that stress the split: no light at all, three lights over four ranks
// (a rank with none), and every light but a few at one point (one Morton code).
TEST(MpiBake, TheSplitLbvhWritesTheInProcessTreeForUnevenShares) {
    SKIP_WITHOUT_MPI();
    std::vector<SceneLight> piled = scattered_lights(2000);
    for (size_t i = 0; i < piled.size(); ++i)
        if (i % 50 != 0) piled[i].position = glm::vec3(2.0f, 3.0f, 4.0f);
    for (std::vector<SceneLight> lights : {std::vector<SceneLight>{}, scattered_lights(3), piled}) {
        BakeInputs inputs = lights_only(lights);
        const std::vector<uint8_t> in_process = tree_bytes(run_bake(inputs, {}));
        for (uint32_t ranks : {1u, 2u, 4u}) {
            inputs.ranks = ranks;
            const std::vector<uint8_t> split = tree_bytes(run_bake(inputs, {}));
            EXPECT_EQ(split, in_process) << lights.size() << " lights, " << ranks << " ranks";
            expect_valid_tree(split, lights.size(), ranks);
        }
    }
}

std::string effect_starting(const Result<BuildResult>& built, const std::string& start) {
    for (const std::string& effect : built ? built->report.effects : std::vector<std::string>{})
        if (effect.rfind(start, 0) == 0) return effect;
    return "";
}

// Another builder still gathers every light on rank 0 and builds there.
TEST(MpiBake, AnAgglomerativeTreeOverRanksIsTheInProcessTree) {
    SKIP_WITHOUT_MPI();
    BakeInputs inputs = cornell_inputs();
    inputs.build.builder = BuilderKind::kAgglomerative;
    inputs.indirect.vpl.particle_count = 1001;
    inputs.indirect.vpl.bounces = bake::kMaxVplBounces;  // the default: until Russian roulette ends a path
    const std::vector<uint8_t> in_process = tree_bytes(run_bake(inputs, {}));
    inputs.ranks = 3;
    const Result<BuildResult> built = run_bake(inputs, {});
    EXPECT_EQ(tree_bytes(built), in_process);
    // No cap to print (the ranks' summary said "65535 bounces").
    const std::string census = effect_starting(built, "indirect: simulated (");
    EXPECT_NE(census.find(" particles, all bounces until Russian roulette, 3 ranks)"), std::string::npos) << census;
}

TEST(MpiBake, TheTreeIsTheSameAtOneToFourRanksAsInOneProcess) {
    SKIP_WITHOUT_MPI();
    BakeInputs inputs = cornell_inputs();
    const Result<BuildResult> whole = run_bake(inputs, {});
    const std::vector<uint8_t> in_process = tree_bytes(whole);
    ASSERT_FALSE(in_process.empty());
    // The tree's lights by kind: the 8 punctual, 301 area samples, the sky's 203, the kept VPLs.
    const TreeLightCounts kinds = whole->report.lights;
    EXPECT_EQ(kinds.punctual, 8u);
    EXPECT_EQ(kinds.area_samples, 301u);
    EXPECT_EQ(kinds.environment, 203u);
    EXPECT_GT(kinds.vpls, 0u);
    EXPECT_EQ(kinds.patches, 0u);
    EXPECT_EQ(kinds.total(), whole->tree.leaf_count);
    for (uint32_t ranks : {1u, 2u, 3u, 4u}) {
        inputs.ranks = ranks;
        Result<BuildResult> built = run_bake(inputs, {});
        const std::vector<uint8_t> bytes = tree_bytes(built);
        EXPECT_EQ(bytes, in_process) << ranks << " ranks";
        if (!built) continue;
        EXPECT_EQ(built->report.lights, kinds) << ranks << " ranks";
        const std::string census = effect_starting(built, "indirect: simulated (");
        EXPECT_NE(census.find(" particles, 3 bounces, "), std::string::npos) << census;
        expect_valid_tree(bytes, (built->channel_file->node_count() + 1) / 2, ranks);
        // One "rank R ..." line per rank: every rank took part.
        size_t rank_lines = 0;
        for (const std::string& effect : built->report.effects) rank_lines += effect.rfind("rank ", 0) == 0;
        EXPECT_EQ(rank_lines, ranks);
    }
}

// The Cornell box's radiosity: about 3,600 patches (15 blocks of 256, several
// for every rank at 4 ranks), a tolerance a float holds exactly (the job
// carries it as one): at 0.5, 1,368 shots.
BakeInputs radiosity_inputs(double tolerance) {
    BakeInputs inputs = cornell_inputs();
    inputs.indirect.method = IndirectMethod::kRadiosity;
    inputs.indirect.radiosity.patch_size = 0.08f;
    inputs.indirect.radiosity.tolerance = tolerance;
    return inputs;
}

TEST(MpiBake, RadiositySplitOverRanksGivesTheInProcessTree) {
    SKIP_WITHOUT_MPI();
    BakeInputs inputs = radiosity_inputs(0.5);
    const Result<BuildResult> whole = run_bake(inputs, {});
    const std::vector<uint8_t> in_process = tree_bytes(whole);
    ASSERT_FALSE(in_process.empty());
    // "indirect: simulated (P patches, all bounces, S steps, U% unshot)"
    const std::string census = effect_starting(whole, "indirect: simulated (");
    ASSERT_NE(census.find(" patches, all bounces, "), std::string::npos) << census;
    EXPECT_GT(whole->report.lights.patches, 0u);
    EXPECT_EQ(whole->report.lights.vpls, 0u);
    EXPECT_EQ(whole->report.lights.total(), whole->tree.leaf_count);
    for (uint32_t ranks : {1u, 2u, 3u, 4u}) {
        inputs.ranks = ranks;
        Result<BuildResult> built = run_bake(inputs, {});
        EXPECT_EQ(tree_bytes(built), in_process) << ranks << " ranks";
        if (built) {
            EXPECT_EQ(built->report.lights, whole->report.lights) << ranks << " ranks";
        }
        // The same shots over every rank count: the census differs only by the rank count.
        EXPECT_EQ(effect_starting(built, "indirect: "),
                  census.substr(0, census.size() - 1) + ", " + std::to_string(ranks) + " ranks)");
        // Every rank shot into some receivers and sent its summaries and lights.
        for (const std::string& effect : built ? built->report.effects : std::vector<std::string>{}) {
            if (ranks > 1 && effect.rfind("rank ", 0) == 0) {
                EXPECT_EQ(effect.find("bytes_sent 0 "), std::string::npos) << effect;
            }
        }
    }
}

TEST(MpiBake, CancelDuringRadiosityStopsEveryRank) {
    SKIP_WITHOUT_MPI();
    BakeInputs inputs = radiosity_inputs(0.001);  // far more shots than the test waits for
    inputs.ranks = 3;
    inputs.mpi.work_dir = fs::temp_directory_path() / ("mpi-radiosity-cancel-" + std::to_string(getpid()));
    fs::create_directories(inputs.mpi.work_dir);
    bool in_radiosity = false;
    Result<BuildResult> cancelled = run_bake(inputs, [&](std::string_view stage, double) {
        in_radiosity = in_radiosity || stage.find("radiosity") != std::string_view::npos;
        return !in_radiosity;
    });
    ASSERT_FALSE(cancelled.ok());
    EXPECT_TRUE(in_radiosity);
    EXPECT_EQ(cancelled.error_kind(), ErrorKind::kCancelled) << cancelled.error();
    EXPECT_EQ(processes_naming(inputs.mpi.work_dir.string()), 0u) << "a rank outlived its cancelled bake";
    fs::remove_all(inputs.mpi.work_dir);
}

TEST(MpiBake, ARankThatDiesFailsTheBakeAndTheNextBakeWorks) {
    SKIP_WITHOUT_MPI();
    BakeInputs inputs = cornell_inputs();
    inputs.ranks = 2;
    inputs.mpi.rank_args = {"--test-die-rank", "1"};
    Result<BuildResult> died = run_bake(inputs, {});
    ASSERT_FALSE(died.ok());
    EXPECT_EQ(died.error_kind(), ErrorKind::kFailed);
    EXPECT_NE(died.error().find("MPI bake over 2 ranks failed"), std::string::npos) << died.error();
    inputs.mpi.rank_args.clear();
    EXPECT_TRUE(run_bake(inputs, {}).ok());
}

// The processes whose command line names `needle`.
size_t processes_naming(const std::string& needle) {
    size_t found = 0;
    for (const auto& entry : fs::directory_iterator("/proc")) {
        std::ifstream in(entry.path() / "cmdline", std::ios::binary);
        std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        found +=
            cmdline.find(needle) != std::string::npos && entry.path().filename() != std::to_string(getpid());
    }
    return found;
}

TEST(MpiBake, CancelStopsEveryRank) {
    SKIP_WITHOUT_MPI();
    BakeInputs inputs = cornell_inputs();
    inputs.ranks = 4;
    inputs.mpi.rank_args = {"--test-stall"};
    inputs.mpi.work_dir = fs::temp_directory_path() / ("mpi-cancel-test-" + std::to_string(getpid()));
    fs::create_directories(inputs.mpi.work_dir);
    bool saw_ranks = false;
    Result<BuildResult> cancelled = run_bake(inputs, [&](std::string_view stage, double) {
        // Cancel once every rank has the job, so the ranks are running when stopped.
        saw_ranks = saw_ranks || stage.find("job received by 4 ranks") != std::string_view::npos;
        return !saw_ranks;
    });
    ASSERT_FALSE(cancelled.ok());
    EXPECT_TRUE(saw_ranks);
    EXPECT_EQ(cancelled.error_kind(), ErrorKind::kCancelled) << cancelled.error();
    EXPECT_EQ(processes_naming(inputs.mpi.work_dir.string()), 0u) << "a rank outlived its cancelled bake";
    fs::remove_all(inputs.mpi.work_dir);
}

// The bake's own stop, with no progress callback to ask: the coordinator polls
// it while it waits on the job. A deadline already passed fails the bake naming
// the limit; a cancel through the stop is a cancel. No rank outlives either.
TEST(MpiBake, TheBakesStopEndsTheJobWithoutAProgressCallback) {
    SKIP_WITHOUT_MPI();
    BakeInputs inputs = cornell_inputs();
    inputs.ranks = 3;
    inputs.mpi.rank_args = {"--test-stall"};
    inputs.mpi.work_dir = fs::temp_directory_path() / ("mpi-stop-test-" + std::to_string(getpid()));
    fs::create_directories(inputs.mpi.work_dir);
    inputs.stop = std::make_shared<BakeStop>(BakeStop::Clock::now(), "--max-bake-seconds 1 (a test's limit)");
    Result<BuildResult> late = run_bake(inputs, {});
    ASSERT_FALSE(late.ok());
    EXPECT_EQ(late.error_kind(), ErrorKind::kFailed) << late.error();
    EXPECT_NE(late.error().find("the MPI job of 3 ranks stopped: the bake ran past --max-bake-seconds 1"),
              std::string::npos)
        << late.error();

    inputs.stop = std::make_shared<BakeStop>();
    inputs.stop->cancel();
    Result<BuildResult> cancelled = run_bake(inputs, {});
    ASSERT_FALSE(cancelled.ok());
    EXPECT_EQ(cancelled.error_kind(), ErrorKind::kCancelled) << cancelled.error();
    EXPECT_EQ(processes_naming(inputs.mpi.work_dir.string()), 0u) << "a rank outlived its stopped bake";
    fs::remove_all(inputs.mpi.work_dir);
}

TEST(MpiBake, MoreRanksThanTheServerAllowsIsRefused) {
    BakeInputs inputs = cornell_inputs();
    inputs.ranks = 5;
    inputs.mpi.max_ranks = 4;
    Result<BuildResult> refused = run_bake(inputs, {});
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error_kind(), ErrorKind::kRefused);
    EXPECT_NE(refused.error().find("asks for 5 MPI ranks; this server allows at most 4"), std::string::npos)
        << refused.error();
}

TEST(MpiBake, AMissingLauncherIsNamed) {
    BakeInputs inputs = cornell_inputs();
    inputs.ranks = 2;
    inputs.mpi.launcher = "no-such-mpirun-for-this-test";
    Result<BuildResult> failed = run_bake(inputs, {});
    ASSERT_FALSE(failed.ok());
    EXPECT_NE(failed.error().find("no-such-mpirun-for-this-test"), std::string::npos) << failed.error();
}

// A folder with a host file naming nodeA and nodeB, and a stand-in for mpirun
// (a shell script `body`) that records each host file it is given into hostfiles.txt.
fs::path fake_cluster(const std::string& name, const std::string& body) {
    const fs::path dir = fs::temp_directory_path() / (name + "-" + std::to_string(getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "hosts.txt") << "nodeA slots=1\nnodeB slots=1\n";
    std::ofstream(dir / "mpirun.sh") << "#!/bin/sh\nwhile [ $# -gt 0 ]; do [ \"$1\" = --hostfile ] && "
                                     << "{ cat \"$2\"; echo ---; } >> " << (dir / "hostfiles.txt")
                                     << "; shift; done\n"
                                     << body;
    fs::permissions(dir / "mpirun.sh", fs::perms::owner_all);
    return dir;
}

BakeInputs on_fake_cluster(const fs::path& dir) {
    BakeInputs inputs = cornell_inputs();
    inputs.ranks = 2;
    inputs.mpi.launcher = (dir / "mpirun.sh").string();
    inputs.mpi.hostfile = dir / "hosts.txt";
    inputs.mpi.work_dir = dir;
    return inputs;
}

std::string text_of(const fs::path& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Ranks that never start (a host that never answers): the bake fails at
// --mpi-launch-seconds naming the flag and the job's hosts; no launcher outlives it.
TEST(MpiBake, RanksThatNeverStartFailTheBakeAtTheLaunchDeadline) {
    const fs::path dir = fake_cluster("mpi-launch-test", "sleep 60\n");
    BakeInputs inputs = on_fake_cluster(dir);
    inputs.mpi.launch_seconds = 1;
    Result<BuildResult> failed = run_bake(inputs, {});
    ASSERT_FALSE(failed.ok());
    EXPECT_NE(failed.error().find("had not all started after 1 s (--mpi-launch-seconds)"), std::string::npos)
        << failed.error();
    EXPECT_NE(failed.error().find("the job's hosts: nodeA, nodeB"), std::string::npos) << failed.error();
    EXPECT_EQ(processes_naming(dir.string()), 0u) << "the launcher outlived its bake";
    fs::remove_all(dir);
}

// mpirun's environment shortens Open MPI's keepalives (a silent host noticed
// in seconds) and keeps the daemons attached, unless the server's own
// environment sets them.
TEST(MpiBake, TheLauncherGetsShortKeepalivesUnlessTheUserSetsThem) {
    const fs::path dir = fake_cluster("mpi-keepalive-test", "");
    std::ofstream(dir / "mpirun.sh", std::ios::app)
        << "env | grep -E 'OMPI_MCA_(oob_tcp_keepalive|orte_leave)' | sort > " << (dir / "env.txt")
        << "\nexit 1\n";
    BakeInputs inputs = on_fake_cluster(dir);
    EXPECT_FALSE(run_bake(inputs, {}).ok());
    EXPECT_EQ(text_of(dir / "env.txt"),
              "OMPI_MCA_oob_tcp_keepalive_intvl=1\nOMPI_MCA_oob_tcp_keepalive_probes=3\n"
              "OMPI_MCA_oob_tcp_keepalive_time=2\nOMPI_MCA_orte_leave_session_attached=1\n");
    setenv("OMPI_MCA_oob_tcp_keepalive_time", "30", 1);
    EXPECT_FALSE(run_bake(inputs, {}).ok());
    unsetenv("OMPI_MCA_oob_tcp_keepalive_time");
    EXPECT_NE(text_of(dir / "env.txt").find("OMPI_MCA_oob_tcp_keepalive_time=30\n"), std::string::npos);
    fs::remove_all(dir);
}

// mpirun says it lost a host's daemon: the bake fails in one line naming the
// host, and the server's next bake gets a host file without it.
TEST(MpiBake, AHostLostMidBakeIsNamedAndLeftOutOfTheNextBake) {
    const fs::path dir = fake_cluster("mpi-lost-host-test",
                                      "printf 'ORTE has lost communication with a remote daemon.\\n"
                                      "  Remote daemon: [[9,0],2] on node nodeB\\n'\nexit 1\n");
    BakeInputs inputs = on_fake_cluster(dir);
    inputs.mpi.lost_hosts = std::make_shared<HostRoster>();
    Result<BuildResult> lost = run_bake(inputs, {});
    ASSERT_FALSE(lost.ok());
    EXPECT_NE(lost.error().find("MPI bake over 2 ranks failed: host nodeB stopped answering"),
              std::string::npos)
        << lost.error();
    EXPECT_EQ(lost.error().find('\n'), std::string::npos) << lost.error();
    EXPECT_FALSE(run_bake(inputs, {}).ok());
    EXPECT_EQ(text_of(dir / "hostfiles.txt"), "nodeA slots=1\nnodeB slots=1\n---\nnodeA slots=1\n---\n");
    fs::remove_all(dir);
}

}  // namespace
}  // namespace lc::bake
