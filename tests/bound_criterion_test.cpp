// The bound criterion (heap search): convergence to the exact value, the
// error within the cut's bounds, the same cut as a brute-force refinement,
// max-cut, and extreme intensities.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "tree_fixtures.h"

namespace lc::test {
namespace {

// The paper's refinement written the slow, obvious way: rescan the cut for the
// largest bound and re-add the total from scratch at every step.
CutResult brute_force_bound_cut(const WalkTree& tree, const SurfacePoint& p, double ratio, uint32_t max_cut) {
    auto key = [&](int32_t i) {
        const GpuTreeNode& n = tree.node(i);
        if (is_leaf(n)) return 0.0;
        if (joins_types(n)) return std::numeric_limits<double>::infinity();
        return max_channel(node_contribution_bound(tree, i, p));
    };
    std::vector<int32_t> cut{0};
    CutResult result;
    while (true) {
        glm::dvec3 total(0.0);
        for (int32_t i : cut) total += shade_node(tree, i, p);
        size_t worst = 0;
        for (size_t k = 1; k < cut.size(); ++k) {
            const double a = key(cut[k]), b = key(cut[worst]);
            if (a > b || (a == b && cut[k] < cut[worst])) worst = k;
        }
        const double worst_key = key(cut[worst]);
        if (!std::isinf(worst_key)) {
            if (worst_key <= 0.0 || worst_key <= ratio * max_channel(total)) break;
            if (cut.size() >= max_cut) {
                result.max_cut_hit = true;
                break;
            }
        }
        int32_t children[2];
        const int count = children_of(tree, cut[worst], children);
        cut.erase(cut.begin() + std::ptrdiff_t(worst));
        cut.insert(cut.end(), children, children + count);
    }
    for (int32_t i : cut) {
        result.radiance += shade_node(tree, i, p);
        result.cut_hash += cut_hash_term(uint32_t(i));
    }
    result.cut_size = uint32_t(cut.size());
    return result;
}

TEST(BoundCriterion, ConvergesToTheExactValueAsErrorRatioGoesToZero) {
    std::mt19937_64 rng(3);
    for (int scene = 0; scene < 4; ++scene) {
        const std::vector<SceneLight> lights = mixed_scene(rng);
        const WalkTree tree = walk_tree(morton_pairing_tree(lights, uint64_t(scene)));
        std::uniform_real_distribution<double> u(-6, 6);
        for (int k = 0; k < 30; ++k) {
            const SurfacePoint p =
                surface({u(rng), u(rng), 0}, {u(rng) * 0.1, u(rng) * 0.1, 1}, {0.8, 0.5, 0.2});
            const glm::dvec3 exact = shade_tree_leaves(tree, p);
            uint32_t previous_cut = 0;
            for (double ratio : {0.1, 0.01, 1e-4, 0.0}) {
                const CutResult r =
                    shade_lightcuts(tree, {}, p, {CutCriterion::kBound, ratio, 100000});
                EXPECT_FALSE(r.max_cut_hit);
                EXPECT_TRUE(finite3(r.radiance));
                expect_within_cut_error(r, exact, ratio);
                EXPECT_GE(r.cut_size, previous_cut) << "a smaller ratio never coarsens the cut";
                previous_cut = r.cut_size;
                if (ratio == 0.0) expect_near_rel(r.radiance, exact, 1e-12, 1e-300);
            }
        }
    }
}

// Street lamps: 64 groups of 64 bulbs over a 200 x 200 plaza. Far groups
// collapse into a few clusters, so cuts stay far smaller than the light count.
TEST(BoundCriterion, ErrorStaysWithinTheSumOfTheCutsBoundsAndCutsAreSublinear) {
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<float> plaza(-100.0f, 100.0f);
    std::vector<SceneLight> lights;
    for (int group = 0; group < 64; ++group) {
        const glm::vec3 lamp(plaza(rng), plaza(rng), 5.0f);
        auto bulbs = random_lights_in_box(rng, 64, LightType::kPoint, lamp - glm::vec3(0.5f),
                                   lamp + glm::vec3(0.5f), false);
        lights.insert(lights.end(), bulbs.begin(), bulbs.end());
    }
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 9));
    std::uniform_real_distribution<double> u(-100, 100);
    uint64_t total_cut = 0;
    for (int k = 0; k < 200; ++k) {
        const SurfacePoint p = surface({u(rng), u(rng), 0});
        const glm::dvec3 exact = shade_tree_leaves(tree, p);
        const CutResult r = shade_lightcuts(tree, {}, p, {CutCriterion::kBound, 0.02, 1000});
        EXPECT_FALSE(r.max_cut_hit);
        total_cut += r.cut_size;
        expect_within_cut_error(r, exact, 0.02);
    }
    const double average_cut = double(total_cut) / 200.0;
    RecordProperty("average_cut_of_4096", std::to_string(average_cut));
    EXPECT_LT(average_cut, 4096.0 / 8.0);
}

TEST(BoundCriterion, PicksTheSameCutAsABruteForceRefinement) {
    std::mt19937_64 rng(31);
    const std::vector<SceneLight> lights = mixed_scene(rng);
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 6));
    std::uniform_real_distribution<double> u(-6, 6);
    int different = 0;
    for (int k = 0; k < 300; ++k) {
        const SurfacePoint p =
            surface({u(rng), u(rng), u(rng) * 0.2}, {u(rng) * 0.2, u(rng) * 0.2, 1});
        for (double ratio : {0.1, 0.02, 0.002}) {
            const uint32_t max_cut = k % 10 == 0 ? 12 : 1000;
            const CutResult fast =
                shade_lightcuts(tree, {}, p, {CutCriterion::kBound, ratio, max_cut, BoundSearch::kHeap});
            const CutResult slow = brute_force_bound_cut(tree, p, ratio, max_cut);
            if (fast.cut_hash != slow.cut_hash) ++different;
            EXPECT_EQ(fast.cut_size, slow.cut_size);
            EXPECT_EQ(fast.max_cut_hit, slow.max_cut_hit);
            expect_near_rel(fast.radiance, slow.radiance, 1e-12, 1e-300);
        }
    }
    EXPECT_EQ(different, 0);
}

TEST(BoundCriterion, MaxCutStopsRefinementAndSaysSo) {
    std::mt19937_64 rng(5);
    std::vector<SceneLight> lights =
        random_lights_in_box(rng, 64, LightType::kPoint, {-2, -2, 1}, {2, 2, 2}, false);
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 2));
    const CutResult r =
        shade_lightcuts(tree, {}, surface({0, 0, 0}), {CutCriterion::kBound, 0.0, 5, BoundSearch::kHeap});
    EXPECT_TRUE(r.max_cut_hit);
    EXPECT_EQ(r.cut_size, 5u);
    const CutResult all =
        shade_lightcuts(tree, {}, surface({0, 0, 0}), {CutCriterion::kBound, 0.0, 64, BoundSearch::kHeap});
    EXPECT_FALSE(all.max_cut_hit);
    EXPECT_EQ(all.cut_size, 64u);
}

TEST(BoundCriterion, ZeroIntensityLightsNeedNoRefinement) {
    std::mt19937_64 rng(8);
    std::vector<SceneLight> lights =
        random_lights_in_box(rng, 16, LightType::kPoint, {-2, -2, 1}, {2, 2, 2}, false);
    for (SceneLight& l : lights) l.intensity = 0.0f;
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 2));
    for (CutCriterion criterion : {CutCriterion::kBound, CutCriterion::kRadius}) {
        const CutResult r = shade_lightcuts(tree, {}, surface({0, 0, 0}), {criterion, 0.02, 1000});
        EXPECT_EQ(r.radiance, glm::dvec3(0.0));
        EXPECT_FALSE(r.max_cut_hit);
    }
    const CutResult bound = shade_lightcuts(tree, {}, surface({0, 0, 0}), {CutCriterion::kBound});
    EXPECT_EQ(bound.cut_size, 1u);  // the root's bound is 0
}

TEST(BoundCriterion, IntensityRatiosOf1e12StayAccurate) {
    std::mt19937_64 rng(13);
    std::vector<SceneLight> lights =
        random_lights_in_box(rng, 32, LightType::kPoint, {-3, -3, 1}, {3, 3, 2}, false);
    for (size_t i = 0; i < lights.size(); ++i) lights[i].intensity = (i % 2 == 0) ? 1e6f : 1e-6f;
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 4));
    std::uniform_real_distribution<double> u(-3, 3);
    for (int k = 0; k < 20; ++k) {
        const SurfacePoint p = surface({u(rng), u(rng), 0});
        const glm::dvec3 exact = shade_tree_leaves(tree, p);
        const CutResult r = shade_lightcuts(tree, {}, p, {CutCriterion::kBound, 0.0, 100000});
        expect_near_rel(r.radiance, exact, 1e-12);
        expect_near_rel(r.radiance, shade_reference(lights, p), 1e-6);  // float node intensities
        const CutResult coarse = shade_lightcuts(tree, {}, p, {CutCriterion::kBound, 0.02, 1000});
        EXPECT_TRUE(finite3(coarse.radiance));
        expect_within_cut_error(coarse, exact, 0.02);
    }
}

TEST(BoundCriterion, PointExactlyOnALightStaysFinite) {
    std::mt19937_64 rng(17);
    std::vector<SceneLight> lights =
        random_lights_in_box(rng, 9, LightType::kPoint, {-1, -1, 0}, {1, 1, 1}, false);
    const WalkTree tree = walk_tree(morton_pairing_tree(lights, 1));
    for (const SceneLight& l : lights) {
        const SurfacePoint p = surface(glm::dvec3(l.position));
        for (CutCriterion criterion : {CutCriterion::kBound, CutCriterion::kRadius}) {
            const CutResult r = shade_lightcuts(tree, {}, p, {criterion, 0.02, 1000});
            EXPECT_TRUE(finite3(r.radiance));
        }
        EXPECT_TRUE(finite3(node_contribution_bound(tree, 0, p)));
    }
}

TEST(BoundCriterion, DirectionalOnlyScenesConverge) {
    std::mt19937_64 rng(19);
    std::vector<SceneLight> suns =
        random_lights_in_box(rng, 50, LightType::kDirectional, {0, 0, 0}, {0, 0, 0}, false);
    const WalkTree tree = walk_tree(morton_pairing_tree(suns, 3));
    const SurfacePoint p = surface({0, 0, 0}, {0.3, -0.2, 1});
    expect_near_rel(shade_lightcuts(tree, {}, p, {CutCriterion::kBound, 0.0, 1000}).radiance,
                    shade_tree_leaves(tree, p), 1e-12);
    expect_near_rel(shade_tree_leaves(tree, p), shade_reference(suns, p), 1e-6);
    // Facing away from every light: the root's bound is zero, one node suffices.
    const SurfacePoint away = surface({0, 0, 0}, {0, 0, -1});
    const CutResult r = shade_lightcuts(tree, {}, away, {CutCriterion::kBound, 0.0, 1000});
    EXPECT_EQ(r.cut_size, 1u);
    EXPECT_EQ(r.radiance, glm::dvec3(0.0));
}

}  // namespace
}  // namespace lc::test
