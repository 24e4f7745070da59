// The parallel builders give byte-identical result channels at any thread
// count: the server's --threads (and TBB's pool) must never change a tree.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstdint>
#include <vector>

#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_records.h"
#include "tree_invariants.h"

namespace lc::bake {
namespace {

using test::random_lights;

// The result channel of one build with TBB held to `threads` workers.
std::vector<uint8_t> channel_with_threads(const std::vector<SceneLight>& lights, BuilderKind builder,
                                          size_t threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    BuildOptions options;
    options.builder = builder;
    options.seed = 5;
    Result<BuildResult> built = build_light_tree(lights, options, {});
    EXPECT_TRUE(built) << built.error();
    if (!built) return {};
    test::expect_tree_invariants(built->tree, lights);
    return encode_result_channel(built->tree);
}

void expect_same_at_any_thread_count(const std::vector<SceneLight>& lights, BuilderKind builder) {
    const std::vector<uint8_t> one = channel_with_threads(lights, builder, 1);
    ASSERT_FALSE(one.empty());
    for (const size_t threads : {2u, 4u}) {
        EXPECT_EQ(channel_with_threads(lights, builder, threads), one) << threads << " threads";
    }
}

std::vector<SceneLight> point_and_spot_lights(uint32_t count) {
    std::vector<SceneLight> lights = random_lights(count, 31, LightType::kPoint);
    const std::vector<SceneLight> spots = random_lights(count / 2, 32, LightType::kSpot);
    for (uint32_t i = 0; i < spots.size(); ++i) {
        lights.push_back(spots[i]);
        lights.back().guid = test::light_guid(count + i);
    }
    return lights;
}

// Enough lights that every parallel loop splits into many tasks.
TEST(BuilderThreadDeterminism, AgglomerativeIsTheSameAtOneTwoAndFourThreads) {
    expect_same_at_any_thread_count(point_and_spot_lights(12000), BuilderKind::kAgglomerative);
}

TEST(BuilderThreadDeterminism, LbvhIsTheSameAtOneTwoAndFourThreads) {
    expect_same_at_any_thread_count(point_and_spot_lights(60000), BuilderKind::kLbvh);
}

TEST(BuilderThreadDeterminism, CoincidentLightsTieTheSameWay) {
    // Equal positions: every tie is broken by index, never by which thread came first.
    std::vector<SceneLight> lights = random_lights(6000, 7, LightType::kPoint, 4.0f);
    for (uint32_t i = 0; i < lights.size(); i += 3) lights[i].position = lights[0].position;
    expect_same_at_any_thread_count(lights, BuilderKind::kAgglomerative);
    expect_same_at_any_thread_count(lights, BuilderKind::kLbvh);
}

}  // namespace
}  // namespace lc::bake
