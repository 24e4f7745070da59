// Bakes over MPI ranks (lightmass_server/mpi/): the light set and the tree the
// same at 1, 2, 3 and 4 ranks as in one process, a rank that dies, a cancelled
// bake, and a bake asking for more ranks than the server allows. The shares'
// determinism is checked without MPI too; the mpirun tests skip, saying why,
// where mpirun or lightmass_rank is missing.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include "indirect_scenes.h"
#include "lightmass_server/bake_pipeline.h"
#include "lightmass_server/emitters/area_light_sampler.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/index_range.h"
#include "lightmass_server/lbvh_builder.h"
#include "lightcuts/seeded_mixer.h"
#include "lightmass_server/indirect/vpl_tracer.h"
#include "protocol/channel_records.h"

namespace lc::bake {
namespace {
namespace fs = std::filesystem;

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

#define SKIP_WITHOUT_MPI()                                                                           \
    do {                                                                                             \
        if (!on_path("mpirun")) GTEST_SKIP() << "mpirun is not on PATH (apt-get install openmpi-bin)"; \
        if (!fs::exists(kRankProgram))                                                               \
            GTEST_SKIP() << kRankProgram << " was not built (CMake found no MPI: libopenmpi-dev)";   \
    } while (0)

// A Cornell box with its emissive panel, a few point lights, VPLs and area samples.
BakeInputs cornell_inputs() {
    BakeInputs inputs;
    auto lights = std::make_shared<std::vector<SceneLight>>();
    for (int i = 0; i < 8; ++i) {
        SceneLight light;
        light.guid = Guid{uint32_t(i + 1), 2, 3, 4};
        light.position = glm::vec3(0.2f + 0.08f * float(i), 0.8f, 0.3f + 0.05f * float(i));
        light.intensity = 0.5f + float(i);
        lights->push_back(light);
    }
    inputs.lights = lights;
    inputs.geometry = std::make_shared<SceneGeometry>(test::cornell_box().geometry);
    inputs.area_lights = 301;  // not a multiple of any rank count
    auto sky = std::make_shared<Environment>();
    sky->sky = SkyParameters{30.0f, 40.0f, 3.0f};
    sky->intensity = 1e-4f;
    inputs.environment = sky;
    inputs.environment_lights = 203;
    inputs.build.builder = BuilderKind::kLbvh;
    inputs.build.seed = 7;
    inputs.indirect.method = IndirectMethod::kVpl;
    inputs.indirect.vpl.particle_count = 3001;
    inputs.indirect.vpl.bounces = 3;
    inputs.indirect.vpl.seed = 7;
    inputs.mpi.launcher_args = {"--oversubscribe", "--allow-run-as-root", "--mca", "btl", "self,tcp"};
    inputs.mpi.rank_program = kRankProgram;
    return inputs;
}

std::vector<uint8_t> tree_bytes(const Result<BuildResult>& built) {
    EXPECT_TRUE(built.ok()) << (built ? "" : built.error());
    return built ? encode_result_channel(built->tree) : std::vector<uint8_t>{};
}

TEST(IndexShares, CoverTheRangeInOrderWithoutGaps) {
    for (uint32_t parts : {1u, 2u, 3u, 4u, 7u}) {
        uint64_t next = 0;
        for (uint32_t p = 0; p < parts; ++p) {
            const IndexRange share = share_of(10, p, parts);
            EXPECT_EQ(share.begin, next);
            EXPECT_LE(share.end - share.begin, 10 / parts + 1);
            next = share.end;
        }
        EXPECT_EQ(next, 10u);
    }
}

TEST(IndexShares, AreaSamplesOfTheSharesAreTheWholeRunsBytes) {
    const SceneGeometry geometry = test::cornell_box().geometry;
    Result<AreaLightSampling> whole = sample_area_lights(geometry, 301, 5);
    ASSERT_TRUE(whole.ok());
    for (uint32_t parts : {2u, 3u, 4u}) {
        std::vector<SceneLight> joined;
        for (uint32_t p = 0; p < parts; ++p) {
            Result<AreaLightSampling> part = sample_area_lights(geometry, 301, 5, share_of(301, p, parts));
            ASSERT_TRUE(part.ok());
            joined.insert(joined.end(), part->lights.begin(), part->lights.end());
        }
        EXPECT_EQ(encode_scene_channel(joined), encode_scene_channel(whole->lights)) << parts << " shares";
    }
}

// A map with a dark band: strata without power leave gaps in the slots.
Environment banded_map() {
    Environment environment;
    environment.map.width = 64;
    environment.map.height = 32;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 64; ++x)
            environment.map.texels.push_back(x >= 20 && x < 30 ? glm::vec3(0.0f) : glm::vec3(0.1f * float(x % 7), 1.0f, 2.0f));
    return environment;
}

TEST(IndexShares, EnvironmentLightsOfTheSharesAreTheWholeRunsBytes) {
    Environment sky;
    sky.sky = SkyParameters{30.0f, 40.0f, 3.0f};
    for (const Environment& environment : {banded_map(), sky}) {
        Result<EnvironmentLights> whole = sample_environment(environment, 1001, 9);
        ASSERT_TRUE(whole.ok());
        ASSERT_GT(whole->lights.size(), 500u);
        for (uint32_t parts : {2u, 3u, 4u}) {
            std::vector<SceneLight> joined;
            for (uint32_t p = 0; p < parts; ++p) {
                Result<EnvironmentLights> part = sample_environment(environment, 1001, 9, p, parts);
                ASSERT_TRUE(part.ok());
                joined.insert(joined.end(), part->lights.begin(), part->lights.end());
            }
            EXPECT_EQ(encode_scene_channel(joined), encode_scene_channel(whole->lights)) << parts << " shares";
        }
    }
}

TEST(IndexShares, VplPathsOfTheSharesAreTheWholeRunsBytes) {
    const BakeInputs inputs = cornell_inputs();
    Result<RayCaster> caster = RayCaster::build(*inputs.geometry, 1);
    ASSERT_TRUE(caster.ok());
    Result<AreaLightSampling> emitters = sample_area_lights(*inputs.geometry, 64, 1);
    ASSERT_TRUE(emitters.ok());
    Result<VplResult> whole = trace_vpls(*inputs.geometry, *caster, emitters->lights, inputs.indirect.vpl, {});
    ASSERT_TRUE(whole.ok());
    ASSERT_GT(whole->lights.size(), 1000u);
    for (uint32_t parts : {2u, 3u, 4u}) {
        std::vector<IndirectLight> joined;
        for (uint32_t p = 0; p < parts; ++p) {
            VplOptions share = inputs.indirect.vpl;
            share.particles = share_of(share.particle_count, p, parts);
            Result<VplResult> part = trace_vpls(*inputs.geometry, *caster, emitters->lights, share, {});
            ASSERT_TRUE(part.ok());
            joined.insert(joined.end(), part->lights.begin(), part->lights.end());
        }
        ASSERT_EQ(joined.size(), whole->lights.size()) << parts << " shares";
        EXPECT_EQ(0, std::memcmp(joined.data(), whole->lights.data(), joined.size() * sizeof(IndirectLight)));
    }
}

// Lights with coincident positions (equal Morton codes) and two types.
std::vector<SceneLight> scattered_lights(size_t count) {
    std::vector<SceneLight> lights(count);
    SplitMix64 random(11);
    for (size_t i = 0; i < count; ++i) {
        lights[i].guid = Guid{uint32_t(i), 7, 7, 7};
        lights[i].type = i % 5 == 0 ? LightType::kSpot : LightType::kPoint;
        lights[i].position = i % 97 == 0 ? glm::vec3(1.0f)
                                         : glm::vec3(random.uniform(), random.uniform(), random.uniform()) * 10.0f;
        lights[i].intensity = float(0.1 + random.uniform());
    }
    return lights;
}

// The LBVH with its subtrees merged "elsewhere" (merge_lbvh_subtree, in this
// process): the same tree as built whole, for any number of parts.
TEST(LbvhSubtrees, MergedElsewhereTheyGiveTheSameTree) {
    const std::vector<SceneLight> lights = scattered_lights(5000);
    BuildOptions options;
    options.builder = BuilderKind::kLbvh;
    options.seed = 3;
    Result<BuildResult> whole = build_light_tree(lights, options, {});
    ASSERT_TRUE(whole.ok());
    for (uint32_t parts : {2u, 3u, 4u, 7u}) {
        std::vector<std::vector<std::vector<LbvhKey>>> sent(parts);
        size_t subtrees_sent = 0;
        LbvhRemoteMerges remote;
        remote.parts = parts;
        remote.send = [&](uint32_t part, const std::vector<std::span<const LbvhKey>>& subtrees) -> Status {
            sent[part].clear();
            for (const auto& s : subtrees) sent[part].emplace_back(s.begin(), s.end());
            subtrees_sent += subtrees.size();
            return Ok{};
        };
        remote.receive = [&](uint32_t part) -> Result<std::vector<std::vector<BuildNode>>> {
            std::vector<std::vector<BuildNode>> merged;
            for (const std::vector<LbvhKey>& keys : sent[part]) {
                std::vector<SceneLight> their_lights;
                for (const LbvhKey& key : keys) their_lights.push_back(lights[key.leaf]);
                Result<std::vector<BuildNode>> nodes = merge_lbvh_subtree(keys, their_lights, options);
                if (!nodes) return nodes.failure();
                merged.push_back(std::move(nodes.value()));
            }
            return merged;
        };
        BuildOptions split = options;
        split.lbvh_remote = &remote;
        Result<BuildResult> built = build_light_tree(lights, split, {});
        ASSERT_TRUE(built.ok()) << built.error();
        EXPECT_GT(subtrees_sent, 0u) << parts << " parts";
        EXPECT_EQ(encode_result_channel(built->tree), encode_result_channel(whole->tree)) << parts << " parts";
    }
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
        // Every rank but 0 sent merged nodes back (160 bytes each), beyond its lights.
        for (const std::string& effect : built ? built->report.effects : std::vector<std::string>{}) {
            if (effect.rfind("rank ", 0) == 0 && effect.rfind("rank 0 ", 0) != 0) {
                EXPECT_EQ(effect.find("bytes_sent 0 "), std::string::npos) << effect;
            }
        }
    }
}

TEST(MpiBake, TheTreeIsTheSameAtOneToFourRanksAsInOneProcess) {
    SKIP_WITHOUT_MPI();
    BakeInputs inputs = cornell_inputs();
    const std::vector<uint8_t> in_process = tree_bytes(run_bake(inputs, {}));
    ASSERT_FALSE(in_process.empty());
    for (uint32_t ranks : {1u, 2u, 3u, 4u}) {
        inputs.ranks = ranks;
        Result<BuildResult> built = run_bake(inputs, {});
        EXPECT_EQ(tree_bytes(built), in_process) << ranks << " ranks";
        if (!built) continue;
        // One "rank R ..." line per rank: every rank took part.
        size_t rank_lines = 0;
        for (const std::string& effect : built->report.effects) rank_lines += effect.rfind("rank ", 0) == 0;
        EXPECT_EQ(rank_lines, ranks);
    }
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
        found += cmdline.find(needle) != std::string::npos && entry.path().filename() != std::to_string(getpid());
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

}  // namespace
}  // namespace lc::bake
