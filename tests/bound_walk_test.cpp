// The bound criterion's walk search (bound_walk.h): the same cuts as
// threshold cuts found by ancestry, at least as fine as the rule asks, its
// behaviour at max-cut, and agreement with the heap search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "lightcuts/cuts/bound_walk.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "tree_fixtures.h"

namespace lc::test {
namespace {

// The cut at threshold tau computed another way: a node is on the cut when every
// ancestor is refined (bound > tau, or a mixed-type junction) and it is not.
struct ThresholdCut {
    glm::dvec3 radiance{0.0};
    uint32_t size = 0;
    uint32_t hash = 0;
    double worst = 0.0;
};

ThresholdCut cut_by_ancestors(const WalkTree& tree, const SurfacePoint& p, double tau) {
    const size_t n = tree.nodes.size();
    std::vector<int32_t> parent(n, -1);
    std::vector<double> key(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
        int32_t children[2];
        const int count = children_of(tree, int32_t(i), children);
        if (count == 0) continue;
        for (int c = 0; c < count; ++c) parent[size_t(children[c])] = int32_t(i);
        key[i] = joins_types(tree.nodes[i]) ? std::numeric_limits<double>::infinity()
                                            : max_channel(node_contribution_bound(tree, int32_t(i), p));
    }
    auto refined = [&](size_t i) {
        const GpuTreeNode& node = tree.nodes[i];
        return !is_leaf(node) && (joins_types(node) || key[i] > tau);
    };
    ThresholdCut cut;
    for (size_t i = 0; i < n; ++i) {
        if (refined(i)) continue;
        bool reached = true;
        for (int32_t a = parent[i]; a >= 0 && reached; a = parent[size_t(a)])
            reached = refined(size_t(a));
        if (!reached) continue;
        cut.radiance += shade_node(tree, int32_t(i), p);
        cut.size += 1;
        cut.hash += cut_hash_term(uint32_t(i));
        if (!std::isinf(key[i])) cut.worst = std::max(cut.worst, key[i]);
    }
    return cut;
}

// The pass schedule of bound_walk.h written out over cut_by_ancestors.
CutResult walk_by_ancestors(const WalkTree& tree, const SurfacePoint& p, double ratio, uint32_t max_cut) {
    CutResult result;
    double tau = std::numeric_limits<double>::infinity();
    double fit = 0.0, over = 0.0;
    int bisections = -1;  // -1: not bisecting yet
    for (uint32_t pass = 0; pass < kWalkMaxPasses; ++pass) {
        const ThresholdCut cut = cut_by_ancestors(tree, p, tau);
        const bool too_big = pass > 0 && cut.size > max_cut;
        if (too_big) {
            over = tau;
            if (bisections < 0) bisections = 0;
        } else {
            result.radiance = cut.radiance;
            result.cut_size = cut.size;
            result.cut_hash = cut.hash;
            const double limit = ratio * std::max(max_channel(cut.radiance), 0.0);
            if (cut.worst <= limit) return result;
            fit = cut.worst;
            if (bisections < 0) {
                tau = std::max(double(kWalkMargin) * limit, cut.worst / double(kWalkShrink));
                continue;
            }
        }
        if (bisections == int(kWalkBisections)) break;
        ++bisections;
        tau = bisection_threshold(fit, over);
    }
    result.max_cut_hit = true;
    return result;
}

TEST(BoundWalk, FindsTheSameCutsAsThresholdCutsFoundByAncestry) {
    std::mt19937_64 rng(41);
    const std::vector<SceneLight> lights = mixed_scene(rng);
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 6));
    std::uniform_real_distribution<double> u(-6, 6);
    int hits = 0;
    for (int k = 0; k < 300; ++k) {
        const SurfacePoint p =
            surface({u(rng), u(rng), u(rng) * 0.2}, {u(rng) * 0.2, u(rng) * 0.2, 1});
        for (double ratio : {0.1, 0.02, 0.002}) {
            const uint32_t max_cut = k % 10 == 0 ? 12 : 1000;
            const CutResult walk = shade_lightcuts(tree, {}, p, {CutCriterion::kBound, ratio, max_cut});
            const CutResult slow = walk_by_ancestors(tree, p, ratio, max_cut);
            EXPECT_EQ(walk.cut_hash, slow.cut_hash);
            EXPECT_EQ(walk.cut_size, slow.cut_size);
            EXPECT_EQ(walk.max_cut_hit, slow.max_cut_hit);
            expect_near_rel(walk.radiance, slow.radiance, 1e-12, 1e-300);
            hits += walk.max_cut_hit ? 1 : 0;
        }
    }
    EXPECT_GT(hits, 0) << "max-cut 12 should stop some pixels";
}

TEST(BoundWalk, GivesTheNodesOfTheCutItKept) {
    // What an audit of the cut's error reads node by node: the nodes of the
    // pass the result holds (the last that fit, at max-cut), each with its
    // cluster estimate, a partition of the leaves.
    std::mt19937_64 rng(59);
    const std::vector<SceneLight> lights = mixed_scene(rng);
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 7));
    std::uniform_real_distribution<double> u(-6, 6);
    int hits = 0;
    for (int k = 0; k < 100; ++k) {
        const SurfacePoint p =
            surface({u(rng), u(rng), u(rng) * 0.2}, {u(rng) * 0.2, u(rng) * 0.2, 1});
        const uint32_t max_cut = k % 4 == 0 ? 12 : 1000;
        const CutSettings settings{CutCriterion::kBound, 0.005, max_cut};
        std::vector<CutNodeEstimate> nodes;
        const CutResult r = bound_walk_cut(tree, p, settings, &nodes);
        const CutResult plain = bound_walk_cut(tree, p, settings);
        EXPECT_EQ(r.cut_hash, plain.cut_hash);
        ASSERT_EQ(nodes.size(), size_t(r.cut_size));
        glm::dvec3 sum(0.0);
        uint32_t hash = 0;
        std::vector<int> covered(tree.nodes.size(), 0);
        for (const CutNodeEstimate& n : nodes) {
            expect_near_rel(n.estimate, shade_node(tree, n.node, p), 1e-15, 1e-300);
            sum += n.estimate;
            hash += cut_hash_term(uint32_t(n.node));
            std::vector<int32_t> stack{n.node};
            while (!stack.empty()) {
                const int32_t index = stack.back();
                covered[size_t(index)] += 1;
                stack.pop_back();
                int32_t children[2];
                const int count = children_of(tree, index, children);
                stack.insert(stack.end(), children, children + count);
            }
        }
        EXPECT_EQ(hash, r.cut_hash);
        expect_near_rel(sum, r.radiance, 1e-12, 1e-300);
        for (size_t i = 0; i < tree.nodes.size(); ++i) {
            if (is_leaf(tree.nodes[i])) {
                EXPECT_EQ(covered[i], 1) << "leaf " << i;
            }
        }
        hits += r.max_cut_hit ? 1 : 0;
    }
    EXPECT_GT(hits, 0) << "max-cut 12 should stop some points";
}

TEST(BoundWalk, CutIsAtLeastAsFineAsTheRuleAsksAndWithinItsBounds) {
    std::mt19937_64 rng(43);
    const std::vector<SceneLight> lights = mixed_scene(rng);
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 9));
    std::uniform_real_distribution<double> u(-6, 6);
    for (int k = 0; k < 300; ++k) {
        const SurfacePoint p =
            surface({u(rng), u(rng), u(rng) * 0.2}, {u(rng) * 0.3, u(rng) * 0.3, 1});
        for (double ratio : {0.05, 0.01}) {
            const CutResult r = shade_lightcuts(tree, {}, p, {CutCriterion::kBound, ratio, 100000});
            ASSERT_FALSE(r.max_cut_hit);
            // The coarsest cut meeting the rule at the walk's own total refines
            // exactly the nodes whose bound exceeds E x T; the walk refined
            // those and possibly more (its last threshold may sit lower).
            const double limit = ratio * max_channel(r.radiance);
            const ThresholdCut coarsest = cut_by_ancestors(tree, p, limit);
            EXPECT_LE(coarsest.worst, limit);
            EXPECT_GE(r.cut_size, coarsest.size);
            expect_within_cut_error(r, shade_tree_leaves(tree, p), ratio);
        }
    }
}

TEST(BoundWalk, OverMaxCutKeepsTheLastWholePassAndSaysSo) {
    std::mt19937_64 rng(5);
    std::vector<SceneLight> lights =
        random_lights_in_box(rng, 64, LightType::kPoint, {-2, -2, 1}, {2, 2, 2}, false);
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 2));
    const CutResult r = shade_lightcuts(tree, {}, surface({0, 0, 0}), {CutCriterion::kBound, 0.0, 5});
    EXPECT_TRUE(r.max_cut_hit);
    EXPECT_GE(r.cut_size, 1u);
    EXPECT_LE(r.cut_size, 5u);
    EXPECT_GE(r.passes, 2u);
    const CutResult all =
        shade_lightcuts(tree, {}, surface({0, 0, 0}), {CutCriterion::kBound, 0.0, 64});
    EXPECT_FALSE(all.max_cut_hit);
    EXPECT_EQ(all.cut_size, 64u);
    expect_near_rel(all.radiance, shade_tree_leaves(tree, surface({0, 0, 0})), 1e-12);
}

TEST(BoundWalk, AtTheCapKeepsACutCloseToIt) {
    // Found by the accuracy sweep: when a pass overshot max-cut the walk kept
    // the previous pass, up to kWalkShrink times coarser, so a smaller error
    // ratio could give a coarser (and worse) image. It now bisects.
    std::mt19937_64 rng(53);
    const std::vector<SceneLight> lights =
        random_lights_in_box(rng, 3000, LightType::kPoint, {-5, -5, 0.2f}, {5, 5, 3}, false);
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 4));
    std::uniform_real_distribution<double> u(-5, 5);
    double fine_cut = 0.0, coarse_cut = 0.0;
    for (int k = 0; k < 50; ++k) {
        const SurfacePoint p = surface({u(rng), u(rng), 0.0});
        const CutResult fine = shade_lightcuts(tree, {}, p, {CutCriterion::kBound, 0.0005, 100});
        const CutResult coarse = shade_lightcuts(tree, {}, p, {CutCriterion::kBound, 0.2, 100});
        ASSERT_TRUE(fine.max_cut_hit);
        EXPECT_LE(fine.cut_size, 100u);
        EXPECT_GE(fine.cut_size, 50u) << "a cut at the cap should use most of it";
        fine_cut += fine.cut_size;
        coarse_cut += coarse.cut_size;
    }
    EXPECT_GE(fine_cut, coarse_cut);
}

TEST(BoundWalk, AgreesWithTheHeapOnErrorAndCutSizeOverARoom) {
    // Both searches stop under the same rule; their cuts differ in which
    // nodes, not in how good. Over many points the mean error and cut size
    // must be close (the walk's margin makes it slightly finer).
    std::mt19937_64 rng(47);
    const std::vector<SceneLight> lights =
        random_lights_in_box(rng, 2000, LightType::kPoint, {-5, -5, 0.2f}, {5, 5, 3}, false);
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 3));
    std::uniform_real_distribution<double> u(-5, 5);
    double walk_err = 0, heap_err = 0, walk_cut = 0, heap_cut = 0;
    const int points = 200;
    for (int k = 0; k < points; ++k) {
        const SurfacePoint p = surface({u(rng), u(rng), 0.0});
        const double exact = max_channel(shade_tree_leaves(tree, p));
        const CutResult walk = shade_lightcuts(tree, {}, p, {CutCriterion::kBound, 0.02, 1000});
        const CutResult heap =
            shade_lightcuts(tree, {}, p, {CutCriterion::kBound, 0.02, 1000, BoundSearch::kHeap});
        walk_err += std::abs(max_channel(walk.radiance) - exact) / exact;
        heap_err += std::abs(max_channel(heap.radiance) - exact) / exact;
        walk_cut += walk.cut_size;
        heap_cut += heap.cut_size;
    }
    std::printf("  walk: mean error %.4f, cut %.1f; heap: mean error %.4f, cut %.1f\n",
                walk_err / points, walk_cut / points, heap_err / points, heap_cut / points);
    EXPECT_LT(walk_err / points, 0.02);
    EXPECT_LT(walk_err, 1.2 * heap_err);
    EXPECT_GT(walk_cut, 0.8 * heap_cut);
    EXPECT_LT(walk_cut, 1.6 * heap_cut);
}

}  // namespace
}  // namespace lc::test
