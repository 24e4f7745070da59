// The thesis's optimal-pair builder: Figure 9.1 exactly, tree invariants,
// determinism, the representative rule, per-type trees, progress and cancel.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "lightmass_server/builders/optimal_pair_builder.h"
#include "lightmass_server/builders/tree_builder.h"
#include "tree_invariants.h"

namespace lc::bake {
namespace {

using test::expect_build_invariants;
using test::expect_tree_invariants;
using test::random_lights;

// The thesis's Figure 9.1: five point lights, range 250, z = 150.
std::vector<SceneLight> figure_9_1_lights() {
    const glm::vec2 xy[5] = {{-300, 0}, {-225, -45}, {-300, 150}, {0, 0}, {150, 0}};
    const float brightness[5] = {5000, 7500, 5000, 5000, 5000};
    std::vector<SceneLight> lights(5);
    for (uint32_t i = 0; i < 5; ++i) {
        lights[i].guid = test::light_guid(i);
        lights[i].type = LightType::kPoint;
        lights[i].position = glm::vec3(xy[i], 150.0f);
        lights[i].intensity = brightness[i];
        lights[i].range = 250.0f;
    }
    return lights;
}

BuildOptions thesis_options() {
    BuildOptions options;
    options.builder = BuilderKind::kOptimalPair;
    options.representative_rule = RepresentativeRule::kThesisFirst;
    options.pairing = PairingMode::kExact;
    return options;
}

// Field-by-field equality of two exported trees (bytes of every float).
void expect_identical_trees(const LightTree& a, const LightTree& b) {
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    EXPECT_EQ(a.leaf_count, b.leaf_count);
    for (size_t i = 0; i < a.nodes.size(); ++i) {
        const LightTreeNode& x = a.nodes[i];
        const LightTreeNode& y = b.nodes[i];
        EXPECT_EQ(x.guid, y.guid) << i;
        EXPECT_EQ(x.type, y.type) << i;
        EXPECT_EQ(x.left, y.left) << i;
        EXPECT_EQ(x.right, y.right) << i;
        EXPECT_EQ(x.representative, y.representative) << i;
        EXPECT_EQ(x.flags.mixed_types(), y.flags.mixed_types()) << i;
        EXPECT_EQ(std::memcmp(&x.position, &y.position, sizeof x.position), 0) << i;
        EXPECT_EQ(std::memcmp(&x.intensity, &y.intensity, sizeof x.intensity), 0) << i;
        EXPECT_EQ(std::memcmp(&x.bbox_min, &y.bbox_min, sizeof x.bbox_min), 0) << i;
        EXPECT_EQ(std::memcmp(&x.bbox_max, &y.bbox_max, sizeof x.bbox_max), 0) << i;
        EXPECT_EQ(std::memcmp(&x.cone_axis, &y.cone_axis, sizeof x.cone_axis), 0) << i;
        EXPECT_EQ(std::memcmp(&x.radius, &y.radius, sizeof x.radius), 0) << i;
        EXPECT_EQ(std::memcmp(&x.cone_cos, &y.cone_cos, sizeof x.cone_cos), 0) << i;
        EXPECT_EQ(std::memcmp(&x.brightness, &y.brightness, sizeof x.brightness), 0) << i;
    }
}

TEST(OptimalPairBuilder, ReproducesThesisFigure9_1) {
    const std::vector<SceneLight> lights = figure_9_1_lights();
    Result<BuildResult> built = build_light_tree(lights, thesis_options(), {});
    ASSERT_TRUE(built) << built.error();
    const LightTree& tree = built->tree;
    ASSERT_EQ(tree.nodes.size(), 9u);
    expect_tree_invariants(tree, lights);

    // Breadth-first: root, {ABC, DE}, {AB, C, D, E}, {A, B}.
    const LightTreeNode& root = tree.nodes[0];
    EXPECT_FLOAT_EQ(root.brightness, 27500.0f);
    EXPECT_NEAR(root.radius, 700.0f, 1e-3f);
    const LightTreeNode& abc = tree.nodes[size_t(root.left)];
    const LightTreeNode& de = tree.nodes[size_t(root.right)];
    EXPECT_FLOAT_EQ(abc.brightness, 17500.0f);
    EXPECT_NEAR(abc.radius, 400.0f, 1e-3f);
    EXPECT_FLOAT_EQ(de.brightness, 10000.0f);
    EXPECT_NEAR(de.radius, 400.0f, 1e-3f);
    const LightTreeNode& ab = tree.nodes[size_t(abc.left)];
    const LightTreeNode& c = tree.nodes[size_t(abc.right)];
    EXPECT_FLOAT_EQ(ab.brightness, 12500.0f);
    EXPECT_NEAR(ab.radius, 337.464f, 1e-3f);
    EXPECT_TRUE(c.is_leaf());
    EXPECT_EQ(c.guid, lights[2].guid);
    const LightTreeNode& a = tree.nodes[size_t(ab.left)];
    const LightTreeNode& b = tree.nodes[size_t(ab.right)];
    EXPECT_EQ(a.guid, lights[0].guid);
    EXPECT_EQ(b.guid, lights[1].guid);
    EXPECT_EQ(tree.nodes[size_t(de.left)].guid, lights[3].guid);
    EXPECT_EQ(tree.nodes[size_t(de.right)].guid, lights[4].guid);

    // Representatives: the first light of each pair (thesis rule).
    EXPECT_EQ(root.representative, ab.left);
    EXPECT_EQ(abc.representative, ab.left);
    EXPECT_EQ(ab.representative, ab.left);
    EXPECT_EQ(de.representative, de.left);
    EXPECT_EQ(root.position, glm::vec3(-300, 0, 150));
    EXPECT_EQ(de.position, glm::vec3(0, 0, 150));
    EXPECT_EQ(root.guid, Guid::combine(abc.guid, de.guid));

    // Level costs: 87.464 + 150, then 150, then 300; every level exact.
    const BuildReport& report = built->report;
    EXPECT_TRUE(report.exact);
    EXPECT_EQ(report.levels, 3u);
    EXPECT_EQ(report.depth, 3u);
    EXPECT_NEAR(report.pairing_cost, std::sqrt(75.0 * 75.0 + 45.0 * 45.0) + 600.0, 1e-9);
    EXPECT_DOUBLE_EQ(report.pairing_lower_bound, report.pairing_cost);
    EXPECT_TRUE(report.warnings.empty());
}

TEST(OptimalPairBuilder, FigureRadiiInDoublePrecision) {
    const std::vector<SceneLight> lights = figure_9_1_lights();
    BuildArena arena = test::leaf_arena(lights);
    const std::vector<uint32_t> leaves = test::all_indices(lights.size());
    BuildReport report;
    Result<int32_t> root = build_optimal_pair_tree(arena, leaves, thesis_options(), {}, report);
    ASSERT_TRUE(root);
    EXPECT_NEAR(arena.nodes[size_t(*root)].radius, 700.0, 1e-9);
    // Arena order: level 0 appends AB then DE, level 1 appends ABC.
    EXPECT_NEAR(arena.nodes[5].radius, 250.0 + std::sqrt(75.0 * 75.0 + 45.0 * 45.0), 1e-9);
    EXPECT_NEAR(arena.nodes[5].radius, 337.464, 1e-3);
    EXPECT_NEAR(arena.nodes[6].radius, 400.0, 1e-9);
    EXPECT_NEAR(arena.nodes[7].radius, 400.0, 1e-9);
    expect_build_invariants(arena, *root, leaves);
}

TEST(OptimalPairBuilder, InvariantsHoldOnRandomScenesOfEveryType) {
    for (LightType type : {LightType::kPoint, LightType::kSpot, LightType::kDirectional}) {
        for (uint32_t n : {2u, 3u, 17u, 64u, 65u, 301u}) {
            const std::vector<SceneLight> lights = random_lights(n, n * 7 + uint32_t(type), type);
            BuildArena arena = test::leaf_arena(lights);
            const std::vector<uint32_t> leaves = test::all_indices(n);
            BuildOptions options;
            options.seed = 42;
            BuildReport report;
            Result<int32_t> root = build_optimal_pair_tree(arena, leaves, options, {}, report);
            ASSERT_TRUE(root) << root.error();
            expect_build_invariants(arena, *root, leaves);
            EXPECT_TRUE(report.exact);
            // A level of m nodes pairs floor(m/2): ceil(log2 n) levels.
            EXPECT_EQ(report.levels, uint32_t(std::ceil(std::log2(double(n)))));

            Result<BuildResult> built = build_light_tree(lights, options, {});
            ASSERT_TRUE(built) << built.error();
            expect_tree_invariants(built->tree, lights);
        }
    }
}

TEST(OptimalPairBuilder, IsDeterministicAndSeedsOnlyMoveRepresentatives) {
    const std::vector<SceneLight> lights = random_lights(500, 3, LightType::kSpot);
    BuildOptions options;
    options.seed = 7;
    Result<BuildResult> first = build_light_tree(lights, options, {});
    Result<BuildResult> second = build_light_tree(lights, options, {});
    ASSERT_TRUE(first && second);
    expect_identical_trees(first->tree, second->tree);
    EXPECT_EQ(first->report.pairing_cost, second->report.pairing_cost);

    // Thesis rule: the seed plays no part.
    BuildOptions thesis = thesis_options();
    thesis.seed = 1;
    Result<BuildResult> t1 = build_light_tree(lights, thesis, {});
    thesis.seed = 99;
    Result<BuildResult> t2 = build_light_tree(lights, thesis, {});
    ASSERT_TRUE(t1 && t2);
    expect_identical_trees(t1->tree, t2->tree);

    // Intensity rule: another seed keeps level 0 (it pairs leaves) but changes
    // some first-level representatives, hence later levels.
    BuildArena arena_a = test::leaf_arena(lights);
    BuildArena arena_b = test::leaf_arena(lights);
    const std::vector<uint32_t> leaves = test::all_indices(lights.size());
    BuildReport ra, rb;
    options.seed = 1;
    ASSERT_TRUE(build_optimal_pair_tree(arena_a, leaves, options, {}, ra));
    options.seed = 2;
    ASSERT_TRUE(build_optimal_pair_tree(arena_b, leaves, options, {}, rb));
    size_t differing_representatives = 0;
    for (size_t i = lights.size(); i < lights.size() + 250; ++i) {
        EXPECT_EQ(arena_a.nodes[i].left, arena_b.nodes[i].left);
        EXPECT_EQ(arena_a.nodes[i].right, arena_b.nodes[i].right);
        EXPECT_EQ(arena_a.nodes[i].guid, arena_b.nodes[i].guid);
        if (arena_a.nodes[i].representative != arena_b.nodes[i].representative) {
            ++differing_representatives;
        }
    }
    EXPECT_GT(differing_representatives, 50u);
    EXPECT_LT(differing_representatives, 200u);
}

TEST(OptimalPairBuilder, RepresentativeProbabilityFollowsIntensity) {
    // Two lights of intensity 1 and 3: the second represents with p = 3/4.
    std::vector<SceneLight> lights = random_lights(2, 1, LightType::kPoint);
    lights[0].intensity = 1.0f;
    lights[1].intensity = 3.0f;
    lights[0].color = lights[1].color = glm::vec3(1.0f);
    int second = 0;
    const int trials = 4000;
    for (int seed = 0; seed < trials; ++seed) {
        BuildOptions options;
        options.seed = uint64_t(seed);
        Result<BuildResult> built = build_light_tree(lights, options, {});
        ASSERT_TRUE(built);
        const LightTreeNode& root = built->tree.nodes[0];
        if (built->tree.nodes[size_t(root.representative)].guid == lights[1].guid) ++second;
    }
    // Binomial(4000, 0.75): standard deviation 27; allow 5 sigma.
    EXPECT_NEAR(second, 3000, 137);
}

TEST(OptimalPairBuilder, TypesGetSeparateTreesJoinedByJunctions) {
    std::vector<SceneLight> lights;
    for (LightType type : {LightType::kDirectional, LightType::kPoint, LightType::kSpot}) {
        for (SceneLight light : random_lights(9, uint64_t(type) + 5, type)) {
            light.guid = test::light_guid(uint32_t(lights.size()));
            lights.push_back(light);
        }
    }
    Result<BuildResult> built = build_light_tree(lights, BuildOptions{}, {});
    ASSERT_TRUE(built) << built.error();
    expect_tree_invariants(built->tree, lights);
    const LightTree& tree = built->tree;
    size_t junctions = 0;
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        const LightTreeNode& node = tree.nodes[i];
        if (node.flags.mixed_types()) {
            ++junctions;
            EXPECT_EQ(node.radius, kUnboundedRadius);
            continue;
        }
        if (node.is_leaf()) continue;
        // Clusters never mix types.
        EXPECT_EQ(tree.nodes[size_t(node.left)].type, node.type);
        EXPECT_EQ(tree.nodes[size_t(node.right)].type, node.type);
    }
    EXPECT_EQ(junctions, 2u);
    EXPECT_TRUE(tree.nodes[0].flags.mixed_types());

    // One type: no junction.
    const std::vector<SceneLight> points = random_lights(9, 1, LightType::kPoint);
    Result<BuildResult> single = build_light_tree(points, BuildOptions{}, {});
    ASSERT_TRUE(single);
    for (const LightTreeNode& node : single->tree.nodes) EXPECT_FALSE(node.flags.mixed_types());
}

TEST(OptimalPairBuilder, AutoModeGoesApproximateAboveTheLimitAndSaysSo) {
    const std::vector<SceneLight> lights = random_lights(100, 8, LightType::kPoint);
    BuildOptions options;
    options.exact_pairing_limit = 30;
    Result<BuildResult> built = build_light_tree(lights, options, {});
    ASSERT_TRUE(built) << built.error();
    const BuildReport& report = built->report;
    EXPECT_FALSE(report.exact);
    ASSERT_EQ(report.warnings.size(), 2u);  // levels of 100 and 50 nodes
    EXPECT_NE(report.warnings[0].find("100"), std::string::npos) << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("limit 30"), std::string::npos) << report.warnings[0];
    EXPECT_NE(report.warnings[1].find("50"), std::string::npos) << report.warnings[1];
    EXPECT_LE(report.pairing_lower_bound, report.pairing_cost);
    EXPECT_GT(report.pairing_lower_bound, 0.0);
    expect_tree_invariants(built->tree, lights);

    options.pairing = PairingMode::kExact;
    Result<BuildResult> exact = build_light_tree(lights, options, {});
    ASSERT_TRUE(exact);
    EXPECT_TRUE(exact->report.exact);
    EXPECT_TRUE(exact->report.warnings.empty());
}

TEST(OptimalPairBuilder, ReportsProgressAndStopsWhenCancelled) {
    const std::vector<SceneLight> lights = random_lights(200, 4, LightType::kPoint);
    std::vector<double> percents;
    Result<BuildResult> built =
        build_light_tree(lights, BuildOptions{}, [&](std::string_view stage, double percent) {
            EXPECT_FALSE(stage.empty());
            percents.push_back(percent);
            return true;
        });
    ASSERT_TRUE(built);
    ASSERT_GE(percents.size(), 8u);  // one per level, then done
    for (size_t i = 1; i < percents.size(); ++i) EXPECT_GE(percents[i], percents[i - 1]);
    EXPECT_DOUBLE_EQ(percents.back(), 100.0);

    int calls = 0;
    Result<BuildResult> cancelled = build_light_tree(
        lights, BuildOptions{}, [&](std::string_view, double) { return ++calls < 3; });
    ASSERT_FALSE(cancelled);
    EXPECT_EQ(cancelled.error_kind(), ErrorKind::kCancelled) << cancelled.error();
    EXPECT_EQ(calls, 3);
}

TEST(OptimalPairBuilder, BuildsFourThousandLightsExactly) {
    const std::vector<SceneLight> lights = random_lights(4096, 12, LightType::kPoint);
    const auto start = std::chrono::steady_clock::now();
    Result<BuildResult> built = build_light_tree(lights, BuildOptions{}, {});
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(built) << built.error();
    EXPECT_TRUE(built->report.exact);
    EXPECT_EQ(built->report.levels, 12u);
    expect_tree_invariants(built->tree, lights);
    std::printf("4096 lights, optimal-pair exact: %.2f s, cost %.3f\n", seconds,
                built->report.pairing_cost);
}

}  // namespace
}  // namespace lc::bake
