// The radius criterion's cuts on the thesis's Figure 9.1 tree, mixed-type
// junctions, classic lights, and a chain too deep for recursion.
#include <gtest/gtest.h>

#include <initializer_list>
#include <span>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "tree_fixtures.h"

namespace lc::test {
namespace {

uint32_t hash_of(std::initializer_list<uint32_t> nodes) {
    uint32_t h = 0;
    for (uint32_t n : nodes) h += cut_hash_term(n);
    return h;
}

TEST(RadiusCriterion, PicksTheExpectedCutsOnTheThesisTree) {
    const LightTree tree = thesis_tree();
    const CutSettings radius{CutCriterion::kRadius};
    struct Case {
        glm::dvec3 point;
        std::vector<uint32_t> cut;
    };
    const std::vector<Case> cases{
        {{1000, 0, 0}, {0}},              // 1308 from A: outside the root's 700
        {{300, 0, 0}, {1, 5, 6}},         // 618 from A (> 400), 335 from D (< 400)
        {{-300, -500, 0}, {1, 2}},        // 522 from A, 601 from D
        {{-300, 0, 0}, {7, 8, 4, 5, 6}},  // 150 from A, 335 from D: every leaf
    };
    for (const Case& c : cases) {
        const SurfacePoint p = surface(c.point);
        const WalkTree walk = walk_tree(tree);
        const CutResult r = shade_lightcuts(walk, {}, p, radius);
        EXPECT_EQ(r.cut_size, c.cut.size()) << "at x = " << c.point.x << ", y = " << c.point.y;
        uint32_t h = 0;
        glm::dvec3 expected(0.0);
        for (uint32_t n : c.cut) {
            h += cut_hash_term(n);
            expected += shade_node(walk, n, p);
        }
        EXPECT_EQ(r.cut_hash, h) << "at x = " << c.point.x << ", y = " << c.point.y;
        expect_near_rel(r.radiance, expected, 1e-12);
        EXPECT_FALSE(r.max_cut_hit);
    }
    // Distinct cuts hash differently.
    EXPECT_NE(hash_of({0}), hash_of({1, 2}));
    EXPECT_NE(hash_of({1, 5, 6}), hash_of({1, 2}));
}

TEST(RadiusCriterion, MixedJunctionsAreAlwaysRefinedAndClassicLightsAdded) {
    LightTree tree = thesis_tree();
    const SurfacePoint p = surface({1000, 0, 0});
    tree.nodes[0].flags.set(kNodeMixedTypes, true);
    SceneLight classic = make_light(LightType::kPoint, {1000, 0, 10}, 100.0f);
    const WalkTree walk = walk_tree(tree);
    const CutResult r = shade_lightcuts(walk, std::span(&classic, 1), p, {CutCriterion::kRadius});
    EXPECT_EQ(r.cut_size, 2u);  // the junction's children, not the junction
    EXPECT_EQ(r.cut_hash, hash_of({1, 2}));
    expect_near_rel(r.radiance, shade_node(walk, 1, p) + shade_node(walk, 2, p) + shade_light(classic, p),
                    1e-12);
    EXPECT_GT(r.radiance.x, 0.9 / kPi);  // 100 cd at 10 units
}

TEST(RadiusCriterion, EmptyTreeGivesOnlyClassicLights) {
    SceneLight classic = make_light(LightType::kPoint, {0, 0, 1}, 1.0f);
    const CutResult r =
        shade_lightcuts(WalkTree{}, std::span(&classic, 1), surface({0, 0, 0}), {CutCriterion::kRadius});
    EXPECT_EQ(r.cut_size, 0u);
    expect_near_rel(r.radiance, glm::dvec3(1.0 / kPi), 1e-12);
}

TEST(RadiusCriterion, DeepChainDoesNotOverflowTheStack) {
    // A chain of depth ~ N (every internal node has a leaf and the next chain node).
    constexpr int kLeaves = 100000;
    LightTree tree;
    tree.nodes.resize(2 * kLeaves - 1);
    for (int i = 0; i < kLeaves - 1; ++i) {
        LightTreeNode& n = tree.nodes[size_t(2 * i)];
        n.left = 2 * i + 1;
        n.right = 2 * i + 2;
        n.radius = kUnboundedRadius;
        n.representative = 2 * i + 1;
    }
    for (int i = 0; i < kLeaves; ++i) {
        const int index = i == kLeaves - 1 ? 2 * i : 2 * i + 1;
        LightTreeNode& leaf = tree.nodes[size_t(index)];
        leaf.left = leaf.right = kNoChild;
        leaf.position = glm::vec3(float(i % 100), float(i / 100) * 0.01f, 5.0f);
        leaf.intensity = glm::vec3(1.0f);
        leaf.bbox_min = leaf.bbox_max = leaf.position;
    }
    tree.leaf_count = kLeaves;
    const SurfacePoint p = surface({50, 5, 0});
    const WalkTree walk = walk_tree(tree);
    const CutResult r = shade_lightcuts(walk, {}, p, {CutCriterion::kRadius});
    EXPECT_EQ(r.cut_size, uint32_t(kLeaves));
    expect_near_rel(r.radiance, shade_tree_leaves(walk, p), 1e-10);
}

}  // namespace
}  // namespace lc::test
