// The compact tree node (lightcuts/tree/compact_node.h) is conservative: every
// leaf's position (its direction for directional lights) lies inside each
// ancestor's decoded box, and every spot direction inside each ancestor's
// decoded cone, on random trees and on hard ones. Also the octahedral packing.
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "lightcuts/tree/compact_node.h"
#include "lightcuts/tree/gpu_layout.h"
#include "lightmass_server/builders/tree_builder.h"
#include "tree_invariants.h"

namespace lc {
namespace {

bool inside(const glm::dvec3& v, const glm::dvec3& lo, const glm::dvec3& hi) {
    return v.x >= lo.x && v.y >= lo.y && v.z >= lo.z && v.x <= hi.x && v.y <= hi.y && v.z <= hi.z;
}

// Every leaf under every node, checked against the node's decoded bounds
// (an explicit stack per node: trees may be chains).
void expect_conservative(const LightTree& tree) {
    Result<WalkTree> gpu = make_walk_tree(tree);
    ASSERT_TRUE(gpu) << gpu.error();
    ASSERT_EQ(gpu->nodes.size(), tree.nodes.size());
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        const LightTreeNode& cluster = tree.nodes[i];
        const CompactBounds bounds = decode_bounds(gpu->nodes[i]);
        EXPECT_LE(bounds.cone_cos, double(cluster.cone_cos)) << "node " << i << ": narrowed";
        const bool spot_cluster = (cluster.type == LightType::kSpot ||
                                   cluster.type == LightType::kOriented) &&
                                  !cluster.flags.mixed_types();
        std::vector<int32_t> stack{int32_t(i)};
        while (!stack.empty()) {
            const LightTreeNode& node = tree.nodes[size_t(stack.back())];
            stack.pop_back();
            if (!node.is_leaf()) {
                for (int32_t child : {node.left, node.right})
                    if (child != kNoChild) stack.push_back(child);
                continue;
            }
            if (cluster.flags.mixed_types()) continue;  // never bounded: always refined
            const glm::dvec3 point(node.type == LightType::kDirectional ? node.direction
                                                                         : node.position);
            EXPECT_TRUE(inside(point, bounds.bbox_min, bounds.bbox_max)) << "node " << i;
            if (spot_cluster) {
                const double cos_angle = glm::dot(glm::normalize(glm::dvec3(node.direction)),
                                                  bounds.cone_axis);
                EXPECT_GE(cos_angle, bounds.cone_cos) << "node " << i;
            }
        }
    }
}

LightTree build(const std::vector<SceneLight>& lights, BuilderKind builder) {
    bake::BuildOptions options;
    options.builder = builder;
    options.seed = 5;
    Result<bake::BuildResult> result = bake::build_light_tree(lights, options, {});
    EXPECT_TRUE(result) << (result ? "" : result.error());
    return result ? result->tree : LightTree{};
}

TEST(CompactNode, OctahedralPackingRoundTripsWithinItsResolution) {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> gauss;
    double worst = 0.0;
    for (int k = 0; k < 100000; ++k) {
        glm::dvec3 v(gauss(rng), gauss(rng), gauss(rng));
        if (glm::length(v) < 1e-9) continue;
        v = glm::normalize(v);
        const glm::dvec3 back = decode_octahedral(encode_octahedral(v));
        worst = std::max(worst, std::acos(std::min(1.0, glm::dot(v, back))));
    }
    // 16 bits per coordinate: a few 1e-5 radians at worst.
    EXPECT_LT(worst, 1e-4);
    for (const glm::dvec3 axis : {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0),
                                  glm::dvec3(0, -1, 0)})
        EXPECT_LT(glm::length(decode_octahedral(encode_octahedral(axis)) - axis), 1e-9);
}

TEST(CompactNode, AZeroWidthConeIsWidenedByWhatThePackingMovedItsAxis) {
    LightTreeNode node;
    node.type = LightType::kSpot;
    node.cone_axis = glm::normalize(glm::vec3(1, 2, 3));
    node.cone_cos = 1.0f;
    const CompactBounds bounds = decode_bounds(make_compact_node(node, 0, 0.0f, kNoChild, kEndOfWalk));
    const glm::dvec3 axis = glm::normalize(glm::dvec3(node.cone_axis));
    EXPECT_GT(glm::length(bounds.cone_axis - axis), 0.0);  // the packing moved the axis
    EXPECT_GE(glm::dot(axis, bounds.cone_axis), bounds.cone_cos);
    EXPECT_GT(bounds.cone_cos, std::cos(1e-3));  // by little
}

// The bound loads a node's representative only where the flag says it has a
// range: the flag must follow the representative, leaf or cluster.
TEST(CompactNode, FlagsTheNodesWhoseRepresentativeHasARange) {
    std::vector<SceneLight> lights = test::random_lights(64, 41, LightType::kPoint);
    for (size_t i = 0; i < lights.size(); ++i) lights[i].range = i % 3 == 0 ? 2.5f : 0.0f;
    const LightTree tree = build(lights, BuilderKind::kAgglomerative);
    Result<WalkTree> walk = make_walk_tree(tree);
    ASSERT_TRUE(walk) << walk.error();
    size_t flagged = 0;
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        const GpuTreeNode& node = walk->nodes[i];
        const bool bounded = walk->leaves[node.representative].range > 0.0f;
        EXPECT_EQ((node.flags & kNodeBoundedRepresentative) != 0u, bounded) << "node " << i;
        flagged += bounded ? 1 : 0;
    }
    EXPECT_GT(flagged, 0u);
    EXPECT_LT(flagged, tree.nodes.size());
    EXPECT_EQ(make_compact_node(tree.nodes[0], 0, 0.0f, kNoChild, kEndOfWalk).flags & kNodeBoundedRepresentative,
              0u);
}

TEST(CompactNode, BoundsHoldEveryLeafOnRandomTrees) {
    for (LightType type : {LightType::kPoint, LightType::kSpot, LightType::kDirectional,
                           LightType::kOriented}) {
        for (BuilderKind builder :
             {BuilderKind::kAgglomerative, BuilderKind::kOptimalPair}) {
            SCOPED_TRACE(int(type));
            expect_conservative(build(test::random_lights(300, 17, type), builder));
        }
    }
}

TEST(CompactNode, BoundsHoldEveryLeafOnHardTrees) {
    // Spots that all point one way (a zero-width cone), along the octahedral
    // map's fold (-z) and its edges, coincident, and far from the origin.
    std::vector<SceneLight> lights = test::random_lights(64, 23, LightType::kSpot);
    for (size_t i = 0; i < lights.size(); ++i) {
        const glm::vec3 ways[] = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {0.6f, -0.8f, 0}};
        lights[i].direction = ways[i % 4];
    }
    expect_conservative(build(lights, BuilderKind::kAgglomerative));
    for (SceneLight& light : lights) light.direction = glm::vec3(0, 0, -1);
    expect_conservative(build(lights, BuilderKind::kAgglomerative));
    for (SceneLight& light : lights) light.position = glm::vec3(1e6f, -1e6f, 3.0f);
    expect_conservative(build(lights, BuilderKind::kAgglomerative));
    std::vector<SceneLight> narrow = test::random_lights(200, 29, LightType::kSpot);
    for (SceneLight& light : narrow)
        light.direction = glm::normalize(glm::vec3(0, 0, -1) + 1e-3f * light.direction);
    expect_conservative(build(narrow, BuilderKind::kOptimalPair));
    std::vector<SceneLight> mixed = test::random_lights(40, 31, LightType::kSpot);
    std::vector<SceneLight> points = test::random_lights(40, 37, LightType::kPoint);
    for (size_t i = 0; i < points.size(); ++i) points[i].guid = test::light_guid(uint32_t(100 + i));
    mixed.insert(mixed.end(), points.begin(), points.end());
    expect_conservative(build(mixed, BuilderKind::kAgglomerative));
}

}  // namespace
}  // namespace lc
