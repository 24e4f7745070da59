// The paper's agglomerative builder: the fast locally-ordered build against the
// textbook O(n^2) greedy, tree invariants, determinism, progress and cancel.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "lightmass_server/builders/agglomerative_builder.h"
#include "lightmass_server/builders/lbvh_builder.h"
#include "lightmass_server/builders/optimal_pair_builder.h"
#include "lightmass_server/builders/tree_builder.h"
#include "tree_invariants.h"

namespace lc::bake {
namespace {

using test::expect_build_invariants;
using test::expect_tree_invariants;
using test::random_lights;

BuildOptions agglomerative_options(uint64_t seed = 0) {
    BuildOptions options;
    options.builder = BuilderKind::kAgglomerative;
    options.seed = seed;
    return options;
}

struct TwoBuilds {
    std::vector<SceneLight> lights;
    BuildArena fast, greedy;
    int32_t fast_root = -1, greedy_root = -1;
    MetricParams params;
};

void build_both(TwoBuilds& b, const BuildOptions& options) {
    const std::vector<uint32_t> leaves = test::all_indices(b.lights.size());
    b.fast = test::leaf_arena(b.lights);
    b.greedy = test::leaf_arena(b.lights);
    BuildReport report;
    Result<int32_t> fast = build_agglomerative_tree(b.fast, leaves, options, {}, report);
    Result<int32_t> greedy = build_agglomerative_tree_exact_greedy(b.greedy, leaves, options);
    ASSERT_TRUE(fast) << fast.error();
    ASSERT_TRUE(greedy) << greedy.error();
    b.fast_root = *fast;
    b.greedy_root = *greedy;
    b.params = agglomerative_metric_params(b.fast, leaves);
    expect_build_invariants(b.fast, b.fast_root, leaves);
    expect_build_invariants(b.greedy, b.greedy_root, leaves);
}

TEST(AgglomerativeBuilder, EqualsTheExactGreedyForOmniAndDirectionalLights) {
    // The metric never decreases as a cluster grows, so merging mutual best
    // partners gives the greedy tree itself: same merges, same total metric.
    for (LightType type : {LightType::kPoint, LightType::kDirectional}) {
        for (uint32_t n : {2u, 3u, 10u, 97u, 400u}) {
            TwoBuilds b;
            b.lights = random_lights(n, n + 31 * uint32_t(type), type);
            // Intensities spanning 1e6 make the metric more than a distance.
            for (uint32_t i = 0; i < n; i += 7) b.lights[i].intensity *= 1e6f;
            build_both(b, agglomerative_options(5));
            const double fast = total_cluster_metric(b.fast, b.fast_root, b.params);
            const double greedy = total_cluster_metric(b.greedy, b.greedy_root, b.params);
            EXPECT_NEAR(fast, greedy, 1e-12 * greedy) << light_type_name(type) << " n=" << n;
            // Same merges in another order: the same set of clusters.
            std::vector<Guid> fast_guids, greedy_guids;
            for (size_t i = n; i < b.fast.nodes.size(); ++i)
                fast_guids.push_back(b.fast.nodes[i].guid);
            for (size_t i = n; i < b.greedy.nodes.size(); ++i) {
                greedy_guids.push_back(b.greedy.nodes[i].guid);
            }
            std::sort(fast_guids.begin(), fast_guids.end());
            std::sort(greedy_guids.begin(), greedy_guids.end());
            EXPECT_EQ(fast_guids, greedy_guids);
        }
    }
}

TEST(AgglomerativeBuilder, StaysCloseToTheExactGreedyForSpotLights) {
    // With orientation cones the bounding-cone union is not exactly monotone,
    // so the locally-ordered result may differ slightly from the greedy one.
    for (uint32_t n : {50u, 300u}) {
        TwoBuilds b;
        b.lights = random_lights(n, n + 3, LightType::kSpot);
        build_both(b, agglomerative_options(1));
        EXPECT_GT(b.params.c2, 0.0);
        const double fast = total_cluster_metric(b.fast, b.fast_root, b.params);
        const double greedy = total_cluster_metric(b.greedy, b.greedy_root, b.params);
        EXPECT_NEAR(fast, greedy, 0.02 * greedy) << "n=" << n;
        std::printf("spots n=%u: fast %.6g, greedy %.6g (%+.3f%%)\n", n, fast, greedy,
                    100.0 * (fast / greedy - 1.0));
    }
}

TEST(AgglomerativeBuilder, BeatsOtherBuildersOnTheClusterMetric) {
    // The greedy minimises what the metric measures; a level-by-level pairing
    // does not look at intensity at all.
    std::vector<SceneLight> lights = random_lights(1000, 77, LightType::kPoint);
    for (uint32_t i = 0; i < lights.size(); i += 10) lights[i].intensity *= 1000.0f;
    const std::vector<uint32_t> leaves = test::all_indices(lights.size());
    BuildArena agg = test::leaf_arena(lights);
    BuildArena pair = test::leaf_arena(lights);
    BuildReport report;
    Result<int32_t> a = build_agglomerative_tree(agg, leaves, agglomerative_options(), {}, report);
    BuildArena morton = test::leaf_arena(lights);
    Result<int32_t> p = build_optimal_pair_tree(pair, leaves, BuildOptions{}, {}, report);
    Result<int32_t> m = build_lbvh_tree(morton, leaves, BuildOptions{}, {}, report);
    ASSERT_TRUE(a && p && m);
    expect_build_invariants(morton, *m, leaves);
    const MetricParams params = agglomerative_metric_params(agg, leaves);
    const double agglomerative_total = total_cluster_metric(agg, *a, params);
    const double optimal_pair_total = total_cluster_metric(pair, *p, params);
    const double lbvh_total = total_cluster_metric(morton, *m, params);
    EXPECT_LT(agglomerative_total, optimal_pair_total);
    EXPECT_LT(agglomerative_total, lbvh_total);
    std::printf("total cluster metric: agglomerative %.6g, optimal-pair %.6g, lbvh %.6g\n",
                agglomerative_total, optimal_pair_total, lbvh_total);
}

TEST(AgglomerativeBuilder, IsDeterministicAndValid) {
    const std::vector<SceneLight> lights = random_lights(3000, 9, LightType::kPoint);
    Result<BuildResult> first = build_light_tree(lights, agglomerative_options(3), {});
    Result<BuildResult> second = build_light_tree(lights, agglomerative_options(3), {});
    ASSERT_TRUE(first && second);
    expect_tree_invariants(first->tree, lights);
    ASSERT_EQ(first->tree.nodes.size(), second->tree.nodes.size());
    for (size_t i = 0; i < first->tree.nodes.size(); ++i) {
        const LightTreeNode& x = first->tree.nodes[i];
        const LightTreeNode& y = second->tree.nodes[i];
        ASSERT_EQ(x.guid, y.guid);
        ASSERT_EQ(x.left, y.left);
        ASSERT_EQ(x.right, y.right);
        ASSERT_EQ(x.representative, y.representative);
        ASSERT_EQ(std::memcmp(&x.bbox_min, &y.bbox_min, sizeof x.bbox_min), 0);
        ASSERT_EQ(std::memcmp(&x.radius, &y.radius, sizeof x.radius), 0);
    }
}

TEST(AgglomerativeBuilder, HundredThousandLightsStayValid) {
    const std::vector<SceneLight> lights = random_lights(100000, 21, LightType::kPoint, 1000.0f);
    const auto start = std::chrono::steady_clock::now();
    Result<BuildResult> built = build_light_tree(lights, agglomerative_options(), {});
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(built) << built.error();
    expect_tree_invariants(built->tree, lights);
    std::printf("100000 point lights, agglomerative: %.2f s, depth %u\n", seconds,
                built->report.depth);
}

TEST(AgglomerativeBuilder, ReportsProgressAndStopsWhenCancelled) {
    const std::vector<SceneLight> lights = random_lights(5000, 4, LightType::kPoint);
    size_t calls = 0;
    double last = -1.0;
    Result<BuildResult> built =
        build_light_tree(lights, agglomerative_options(), [&](std::string_view, double percent) {
            EXPECT_GE(percent, last);
            last = percent;
            ++calls;
            return true;
        });
    ASSERT_TRUE(built);
    EXPECT_GE(calls, 100u);  // about every 1% of the merges
    EXPECT_DOUBLE_EQ(last, 100.0);

    size_t cancel_calls = 0;
    Result<BuildResult> cancelled =
        build_light_tree(lights, agglomerative_options(), [&](std::string_view, double percent) {
            ++cancel_calls;
            return percent < 30.0;
        });
    ASSERT_FALSE(cancelled);
    EXPECT_EQ(cancelled.error_kind(), ErrorKind::kCancelled) << cancelled.error();
    EXPECT_LT(cancel_calls, 60u);
}

}  // namespace
}  // namespace lc::bake
