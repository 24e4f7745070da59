// Large trees keep every light: the builders, the export and the result channel
// must not truncate above 2^16 lights (a 131,072-light bake once lost leaves).
#include <gtest/gtest.h>

#include <random>

#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_records.h"

namespace lc {
namespace {

std::vector<SceneLight> random_point_lights(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-5.0f, 5.0f), power(0.01f, 0.1f);
    std::vector<SceneLight> lights(n);
    for (size_t i = 0; i < n; ++i) {
        lights[i].guid = Guid{static_cast<uint32_t>(i), 7, 7, 7};
        lights[i].position = {pos(rng), pos(rng), pos(rng)};
        lights[i].intensity = power(rng);
    }
    return lights;
}

void expect_all_leaves_kept(BuilderKind builder, size_t n) {
    SCOPED_TRACE(builder_name(builder));
    auto lights = random_point_lights(n, 5);
    bake::BuildOptions options;
    options.builder = builder;
    auto built = bake::build_light_tree(lights, options, [](std::string_view, double) { return true; });
    ASSERT_TRUE(built.ok()) << built.error();
    const LightTree& tree = built->tree;
    ASSERT_EQ(tree.leaf_count, n);
    ASSERT_EQ(tree.nodes.size(), 2 * n - 1);
    double expected = 0.0, root = tree.nodes[0].brightness;
    for (const SceneLight& l : lights) expected += l.intensity;
    EXPECT_NEAR(root, expected, expected * 1e-5);
    std::vector<int> seen(n, 0);
    size_t leaves = 0;
    for (const LightTreeNode& node : tree.nodes) {
        if (!node.is_leaf()) continue;
        ++leaves;
        ASSERT_LT(node.guid.a, n);
        ++seen[node.guid.a];
    }
    EXPECT_EQ(leaves, n);
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << "light " << i;

    auto decoded = decode_result_channel(encode_result_channel(tree));
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_EQ(decoded->leaf_count, n);
}

TEST(LargeTree, AgglomerativeKeepsEveryLightAbove65536) {
    expect_all_leaves_kept(BuilderKind::kAgglomerative, 131072);
}
TEST(LargeTree, LbvhKeepsEveryLightAbove65536) { expect_all_leaves_kept(BuilderKind::kLbvh, 131072); }
TEST(LargeTree, OptimalPairKeepsEveryLightAbove65536) {
    expect_all_leaves_kept(BuilderKind::kOptimalPair, 70000);
}

}  // namespace
}  // namespace lc
