// The real-time mode's light-draw records (lightcuts/tree/draw_pairs.h) describe
// the tree they were made from: each internal node's record names its two
// children (a leaf child by its light), weighs them by their intensities and
// bounding spheres, and a descent through the records from any node reaches
// every leaf light below it exactly once, with probabilities that sum to 1.
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <map>
#include <vector>

#include "lightcuts/device/pixel_representative.glsl.h"
#include "lightcuts/tree/draw_pairs.h"
#include "lightcuts/tree/gpu_layout.h"
#include "lightmass_server/builders/tree_builder.h"
#include "tree_invariants.h"

namespace lc {
namespace {

WalkTree gpu_tree(const std::vector<SceneLight>& lights) {
    bake::BuildOptions options;
    options.builder = BuilderKind::kAgglomerative;
    options.seed = 5;
    Result<bake::BuildResult> built = bake::build_light_tree(lights, options, {});
    EXPECT_TRUE(built) << (built ? "" : built.error());
    Result<WalkTree> gpu = make_walk_tree(built->tree);
    EXPECT_TRUE(gpu) << (gpu ? "" : gpu.error());
    return std::move(gpu).value();
}

float weight(const vec3& centre, float radius, float intensity, const vec3& x, const vec3& n) {
    return radius < 0.0f ? intensity
                         : intensity * device::stochastic_sphere_geometry(centre - x, radius, n);
}

// Every leaf light a descent from `node` can reach, with its probability at
// the shading point (x, n): the shader's draw_one_level, enumerated.
void reach(const std::vector<GpuDrawPair>& pairs, int node, double probability, const vec3& x,
           const vec3& n, std::map<uint32_t, double>& leaves) {
    if (node < 0) {
        leaves[uint32_t(~node)] += probability;
        return;
    }
    const GpuDrawPair& pair = pairs[size_t(node)];
    const double w0 = weight(pair.centre0, pair.radius0, pair.intensity0, x, n);
    const double w1 = weight(pair.centre1, pair.radius1, pair.intensity1, x, n);
    if (!(w0 + w1 > 0.0)) return reach(pairs, pair.child0, probability, x, n, leaves);
    if (w0 > 0.0) reach(pairs, pair.child0, probability * w0 / (w0 + w1), x, n, leaves);
    if (w1 > 0.0) reach(pairs, pair.child1, probability * w1 / (w0 + w1), x, n, leaves);
}

TEST(DrawPairs, RecordsNameEachNodesChildrenAndBoundTheirBoxes) {
    const WalkTree tree = gpu_tree(test::random_lights(200, 11, LightType::kPoint));
    const std::vector<GpuDrawPair> pairs = make_draw_pairs(tree.nodes);
    ASSERT_EQ(pairs.size(), tree.nodes.size());
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        const GpuTreeNode& node = tree.nodes[i];
        if (node.first_child == kNoChild) continue;
        const int c0 = node.first_child;
        const int c1 = tree.nodes[size_t(c0)].escape;
        const GpuDrawPair& pair = pairs[i];
        for (auto [child, destination, centre, radius, intensity] :
             {std::tuple{c0, pair.child0, pair.centre0, pair.radius0, pair.intensity0},
              std::tuple{c1, pair.child1, pair.centre1, pair.radius1, pair.intensity1}}) {
            const GpuTreeNode& c = tree.nodes[size_t(child)];
            EXPECT_EQ(destination, c.first_child == kNoChild ? ~int(c.representative) : child);
            EXPECT_EQ(intensity, device::representative_scalar(c.intensity));
            for (const vec3& corner : {c.bbox_min, c.bbox_max}) {
                EXPECT_LE(glm::length(corner - centre), radius) << "node " << i;
            }
        }
    }
}

TEST(DrawPairs, ADescentReachesEveryLeafOnceWithProbabilitiesSummingToOne) {
    for (LightType type : {LightType::kPoint, LightType::kSpot, LightType::kDirectional}) {
        SCOPED_TRACE(int(type));
        const WalkTree tree = gpu_tree(test::random_lights(120, 3, type));
        const std::vector<GpuDrawPair> pairs = make_draw_pairs(tree.nodes);
        // A point inside the lights' volume, facing up: some children lie behind it.
        const vec3 x(0.1f, 0.2f, 0.3f), n(0.0f, 1.0f, 0.0f);
        std::map<uint32_t, double> leaves;
        reach(pairs, 0, 1.0, x, n, leaves);
        double total = 0.0;
        for (const auto& [light, probability] : leaves) {
            EXPECT_LT(light, tree.leaves.size());
            total += probability;
        }
        EXPECT_NEAR(total, 1.0, 1e-9);
        // Directional children weigh by intensity alone: every light is reachable.
        if (type == LightType::kDirectional) {
            EXPECT_EQ(leaves.size(), tree.leaves.size());
        }
    }
}

TEST(DrawPairs, DirectionalAndOneChildNodesAndAnEmptyTree) {
    const WalkTree directional = gpu_tree(test::random_lights(8, 5, LightType::kDirectional));
    for (const GpuDrawPair& pair : make_draw_pairs(directional.nodes)) {
        EXPECT_LT(pair.radius0, 0.0f);
        EXPECT_LT(pair.radius1, 0.0f);
    }
    // A root with one child: the second is never drawn.
    std::vector<GpuTreeNode> chain(2);
    chain[0].first_child = 1;
    chain[1].representative = 0;
    chain[1].intensity = vec3(1.0f);
    const std::vector<GpuDrawPair> one = make_draw_pairs(chain);
    EXPECT_EQ(one[0].child0, ~0);
    EXPECT_EQ(one[0].child1, ~0);
    EXPECT_EQ(one[0].intensity1, 0.0f);
    EXPECT_EQ(make_draw_pairs({}).size(), 1u);
}

}  // namespace
}  // namespace lc
