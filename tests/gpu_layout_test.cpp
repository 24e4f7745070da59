// The conversions into the structs the shaders read (their layout is checked
// against the SPIR-V by shader_interface_test), and the pre-order escape
// indices of the stackless walk on small trees and on a 10^6-node chain.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "lightcuts/tree/gpu_layout.h"
#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/shading_model.h"

namespace lc::client {
namespace {

TEST(GpuLayout, SceneLightConversion) {
    SceneLight light;
    light.type = LightType::kSpot;
    light.position = {1, 2, 3};
    light.direction = {0, -1, 0};
    light.color = {0.5f, 1.0f, 0.25f};
    light.intensity = 8.0f;
    light.range = 7.0f;
    light.inner_cone_angle = 0.2f;
    light.outer_cone_angle = 0.6f;
    GpuLight gpu = make_gpu_light(light);
    EXPECT_EQ(gpu.type, uint32_t(LightType::kSpot));
    EXPECT_FLOAT_EQ(gpu.intensity.x, 4.0f);
    EXPECT_FLOAT_EQ(gpu.intensity.y, 8.0f);
    EXPECT_FLOAT_EQ(gpu.intensity.z, 2.0f);
    EXPECT_FLOAT_EQ(gpu.range, 7.0f);
    EXPECT_FLOAT_EQ(gpu.spot_cos_inner, std::cos(0.2f));
    EXPECT_FLOAT_EQ(gpu.spot_cos_outer, std::cos(0.6f));
    EXPECT_NEAR(gpu.spot_scale, 1.0 / (std::cos(0.2) - std::cos(0.6)), 1e-4);

    // Equal cones: the scale is capped by kSpotMinCosDelta, never infinite.
    light.inner_cone_angle = light.outer_cone_angle = 0.5f;
    EXPECT_FLOAT_EQ(make_gpu_light(light).spot_scale, float(1.0 / shading::kSpotMinCosDelta));
}

LightTreeNode node(int32_t left, int32_t right) {
    LightTreeNode n;
    n.left = left;
    n.right = right;
    return n;
}

// Each inner node represented by its first child's representative, as the
// builders do (children follow their parents, so one backwards pass).
LightTree with_representatives(LightTree tree) {
    for (size_t i = tree.nodes.size(); i-- > 0;) {
        LightTreeNode& n = tree.nodes[i];
        n.representative = n.is_leaf() ? int32_t(i)
                                       : tree.nodes[size_t(n.left != kNoChild ? n.left : n.right)]
                                             .representative;
    }
    return tree;
}

TEST(GpuLayout, EscapeIndicesOfABalancedTree) {
    //        0
    //      1   2
    //     3 4 5 6
    LightTree tree;
    tree.nodes = {node(1, 2),   node(3, 4),   node(5, 6),  node(-1, -1),
                  node(-1, -1), node(-1, -1), node(-1, -1)};
    Result<std::vector<int32_t>> escape = derive_escape_indices(tree);
    ASSERT_TRUE(escape.ok()) << escape.error();
    // Pre-order: 0 1 3 4 2 5 6.
    EXPECT_EQ(*escape, (std::vector<int32_t>{-1, 2, -1, 4, 2, 6, -1}));

    Result<WalkTree> gpu = make_walk_tree(with_representatives(tree));
    ASSERT_TRUE(gpu.ok()) << gpu.error();
    EXPECT_EQ(gpu->nodes[0].first_child, 1);
    EXPECT_EQ(gpu->nodes[1].first_child, 3);
    EXPECT_EQ(gpu->nodes[3].first_child, kNoChild);
    EXPECT_EQ(gpu->leaves.size(), 4u);
    EXPECT_EQ(gpu->depth, 2u);
}

// The walk the shader does, with a refine decision per node: visits each cut
// node once and returns them in pre-order.
std::vector<int32_t> walk(const WalkTree& tree, const std::vector<bool>& refine) {
    std::vector<int32_t> cut;
    int32_t i = tree.nodes.empty() ? kEndOfWalk : 0;
    size_t steps = 0;
    while (i != kEndOfWalk && steps++ < tree.nodes.size()) {
        const GpuTreeNode& n = tree.nodes[i];
        if (n.first_child != kNoChild && refine[i]) {
            i = n.first_child;
        } else {
            cut.push_back(i);
            i = n.escape;
        }
    }
    return cut;
}

TEST(GpuLayout, WalkProducesTheExpectedCuts) {
    // Unbalanced, with an odd carried node and a one-child node:
    //          0
    //       1     2
    //      3 4    5(only left child)
    //            6
    LightTree tree;
    tree.nodes = {node(1, 2),   node(3, 4),  node(5, -1), node(-1, -1),
                  node(-1, -1), node(6, -1), node(-1, -1)};
    Result<WalkTree> gpu = make_walk_tree(with_representatives(tree));
    ASSERT_TRUE(gpu.ok()) << gpu.error();
    std::vector<bool> all(7, true), none(7, false);
    EXPECT_EQ(walk(*gpu, all), (std::vector<int32_t>{3, 4, 6}));
    EXPECT_EQ(walk(*gpu, none), (std::vector<int32_t>{0}));
    std::vector<bool> root_only(7, false);
    root_only[0] = true;
    EXPECT_EQ(walk(*gpu, root_only), (std::vector<int32_t>{1, 2}));
    std::vector<bool> right_side = root_only;
    right_side[2] = true;
    EXPECT_EQ(walk(*gpu, right_side), (std::vector<int32_t>{1, 5}));
}

// The CPU evaluator finds a node's children from the walk links alone: the
// import form's left and right, in that order, one-child nodes included.
TEST(GpuLayout, WalkTreeChildrenAreTheImportedOnes) {
    //          0
    //       1     2
    //      3 4    5 (left only)
    //            6   7 (right only: 7's left is absent)
    //                8
    LightTree tree;
    tree.nodes = {node(1, 2),   node(3, 4), node(5, -1), node(-1, -1), node(-1, -1),
                  node(6, 7),   node(-1, -1), node(-1, 8), node(-1, -1)};
    tree = with_representatives(tree);
    Result<WalkTree> walk = make_walk_tree(tree);
    ASSERT_TRUE(walk.ok()) << walk.error();
    uint32_t leaves = 0;
    for (int32_t i = 0; i < int32_t(tree.nodes.size()); ++i) {
        const LightTreeNode& imported = tree.nodes[size_t(i)];
        std::vector<int32_t> expected;
        for (int32_t child : {imported.left, imported.right})
            if (child != kNoChild) expected.push_back(child);
        int32_t children[2];
        const int count = children_of(*walk, i, children);
        EXPECT_EQ(std::vector<int32_t>(children, children + count), expected) << "node " << i;
        EXPECT_EQ(is_leaf(walk->node(i)), imported.is_leaf()) << "node " << i;
        // A node is evaluated through its representative's leaf light.
        EXPECT_EQ(&walk->light_of(i), &walk->light_of(imported.representative)) << "node " << i;
        if (imported.is_leaf()) {
            EXPECT_EQ(walk->node(i).representative, leaves++) << "node " << i;
        }
    }
    EXPECT_EQ(walk->leaves.size(), size_t(leaves));
}

TEST(GpuLayout, RejectsMalformedTrees) {
    LightTree backwards;
    backwards.nodes = {node(1, 2), node(-1, -1), node(1, -1)};  // 1 has two parents
    EXPECT_FALSE(derive_escape_indices(backwards).ok());
    LightTree out_of_range;
    out_of_range.nodes = {node(1, 5), node(-1, -1)};
    Result<std::vector<int32_t>> r = derive_escape_indices(out_of_range);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().find("out of range"), std::string::npos) << r.error();
    LightTree cycle;
    cycle.nodes = {node(1, -1), node(0, -1)};
    r = derive_escape_indices(cycle);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().find("not greater"), std::string::npos) << r.error();
    LightTree not_finite;
    not_finite.nodes = {node(-1, -1)};
    not_finite.nodes[0].intensity.x = std::nanf("");
    Result<WalkTree> g = make_walk_tree(not_finite);
    ASSERT_FALSE(g.ok());
    EXPECT_NE(g.error().find("intensity"), std::string::npos) << g.error();
    LightTree inner_representative;
    inner_representative.nodes = {node(1, 2), node(-1, -1), node(-1, -1)};
    inner_representative.nodes[0].representative = 0;  // itself, not a leaf
    g = make_walk_tree(inner_representative);
    ASSERT_FALSE(g.ok());
    EXPECT_NE(g.error().find("not a leaf"), std::string::npos) << g.error();
}

TEST(GpuLayout, MillionNodeChainNeedsNoRecursion) {
    // A chain of depth ~N/2: node 2k has children 2k+1 (a leaf) and 2k+2.
    constexpr int32_t kNodes = 1'000'001;
    LightTree chain;
    chain.nodes.resize(kNodes);
    for (int32_t i = 0; i + 2 < kNodes; i += 2) {
        chain.nodes[i].left = i + 1;
        chain.nodes[i].right = i + 2;
    }
    Result<WalkTree> gpu = make_walk_tree(with_representatives(chain));
    ASSERT_TRUE(gpu.ok()) << gpu.error();
    EXPECT_EQ(gpu->depth, uint32_t(kNodes / 2));
    EXPECT_EQ(gpu->leaves.size(), size_t(kNodes / 2 + 1));
    // Each left leaf escapes to its sibling; every right spine node to the end.
    for (int32_t i = 0; i + 2 < kNodes; i += 2) {
        ASSERT_EQ(gpu->nodes[i + 1].escape, i + 2);
        ASSERT_EQ(gpu->nodes[i].escape, kEndOfWalk);
    }
    // Refining everything visits every leaf exactly once, in order.
    std::vector<bool> all(kNodes, true);
    std::vector<int32_t> cut = walk(*gpu, all);
    ASSERT_EQ(cut.size(), size_t(kNodes / 2 + 1));
    EXPECT_EQ(cut.front(), 1);
    EXPECT_EQ(cut.back(), kNodes - 1);
}

}  // namespace
}  // namespace lc::client
