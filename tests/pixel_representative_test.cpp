// Per-pixel representatives (Representatives::kPixel and kImportance) in the
// CPU evaluator: the descent draws each leaf of a cluster with probability
// I_leaf / I_C (counted over many pixels, pinned keys), a parent's pixel
// representative is the one of the child its draw takes, the cluster estimate
// is unbiased over pixels (per channel with kImportance, whose estimate stays
// under the cluster's weight), the searches' reuse of a parent's evaluation
// gives what evaluating each cut node afresh gives, and kTree is the tree's
// representatives.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "lightcuts/cuts/bound_walk.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/device/pixel_representative.glsl.h"
#include "tree_fixtures.h"

namespace lc {
namespace {

// The builder's scalar intensity in float, as the draw reads it.
double scalar_intensity(const GpuTreeNode& node) {
    return double(node.intensity.x + node.intensity.y + node.intensity.z);
}

WalkTree random_tree(int count, uint64_t seed) {
    std::mt19937_64 rng(seed);
    const std::vector<SceneLight> lights = test::random_lights_in_box(
        rng, count, LightType::kPoint, {-4.0f, 1.0f, -4.0f}, {4.0f, 3.0f, 4.0f}, false);
    return test::walk_tree(test::morton_pairing_tree(lights, seed));
}

uint32_t key_of_pixel(uint32_t x, uint32_t y) {
    return device::pixel_representative_key(x, y, 7u);
}

// Every leaf under `index`.
std::vector<int32_t> leaves_under(const WalkTree& tree, int32_t index) {
    std::vector<int32_t> leaves, stack{index};
    while (!stack.empty()) {
        const int32_t i = stack.back();
        stack.pop_back();
        int32_t children[2];
        const int n = children_of(tree, i, children);
        if (n == 0) leaves.push_back(i);
        for (int c = 0; c < n; ++c) stack.push_back(children[c]);
    }
    return leaves;
}

TEST(PixelRepresentative, DrawsEachLeafInProportionToItsIntensity) {
    const WalkTree tree = random_tree(24, 3);
    // The root and a cluster a few levels down, over 256 x 256 pixels.
    for (int32_t cluster : {0, 5}) {
        SCOPED_TRACE(cluster);
        const std::vector<int32_t> leaves = leaves_under(tree, cluster);
        ASSERT_GE(leaves.size(), 3u);
        std::map<int32_t, double> counts;
        const uint32_t side = 256;
        for (uint32_t y = 0; y < side; ++y)
            for (uint32_t x = 0; x < side; ++x)
                counts[pixel_representative(tree, cluster, key_of_pixel(x, y))] += 1.0;
        double leaf_sum = 0.0;
        for (int32_t leaf : leaves) leaf_sum += scalar_intensity(tree.nodes[size_t(leaf)]);
        // Pearson's chi-square over the leaves; the 1e-4 quantile of chi^2
        // with up to 23 degrees of freedom is under 60.
        double chi2 = 0.0, drawn = 0.0;
        for (int32_t leaf : leaves) {
            const double expected =
                double(side * side) * scalar_intensity(tree.nodes[size_t(leaf)]) / leaf_sum;
            ASSERT_GT(expected, 5.0);
            const double observed = counts[leaf];
            chi2 += (observed - expected) * (observed - expected) / expected;
            drawn += observed;
        }
        EXPECT_EQ(drawn, double(side * side)) << "a draw ended outside the cluster's leaves";
        EXPECT_LT(chi2, 60.0);
    }
}

TEST(PixelRepresentative, AParentsRepresentativeIsTheOneOfTheChildItsDrawTakes) {
    const WalkTree tree = random_tree(40, 5);
    for (uint32_t pixel = 0; pixel < 64; ++pixel) {
        const uint32_t key = key_of_pixel(pixel, 3 * pixel);
        for (int32_t i = 0; i < int32_t(tree.nodes.size()); ++i) {
            int32_t children[2];
            const int n = children_of(tree, i, children);
            const int32_t parent_rep = pixel_representative(tree, i, key);
            if (n == 0) {
                EXPECT_EQ(parent_rep, i);
                continue;
            }
            const bool first = n == 1 || device::pixel_takes_first_child(
                                             key, uint32_t(i), tree.nodes[size_t(children[0])].intensity,
                                             tree.nodes[size_t(children[1])].intensity);
            EXPECT_EQ(parent_rep, pixel_representative(tree, children[first ? 0 : 1], key)) << "node " << i;
        }
    }
}

TEST(PixelRepresentative, TheClusterEstimateIsUnbiasedOverPixels) {
    const WalkTree tree = random_tree(32, 11);
    const SurfacePoint p = test::surface({0.5, 0.0, -0.5}, {0.0, 1.0, 0.0});
    CutSettings settings;
    settings.representatives = Representatives::kPixel;
    // The draw follows the scalar intensity (the sum of RGB), so that sum is
    // what the estimate is unbiased for; per channel, coloured lights differ
    // (as with the tree's representatives).
    const auto rgb_sum = [](const glm::dvec3& v) { return v.x + v.y + v.z; };
    for (int32_t cluster : {0, 1, 2}) {
        SCOPED_TRACE(cluster);
        double exact = 0.0;
        for (int32_t leaf : leaves_under(tree, cluster)) exact += rgb_sum(shade_node(tree, leaf, p));
        double mean = 0.0;
        const uint32_t side = 200;
        SurfacePoint q = p;
        for (q.pixel.y = 0; q.pixel.y < side; ++q.pixel.y)
            for (q.pixel.x = 0; q.pixel.x < side; ++q.pixel.x)
                mean += rgb_sum(shade_cluster(tree, cluster, q, settings));
        mean /= double(side * side);
        // 40,000 draws: a few per mille; the tree's one representative for
        // every pixel is off by several per cent.
        EXPECT_NEAR(mean, exact, 0.01 * exact);
        EXPECT_GT(std::abs(rgb_sum(shade_node(tree, cluster, p)) - exact), 0.03 * exact);
    }
}

TEST(PixelRepresentative, SearchesReuseAParentsEvaluationOnlyWhereItIsTheChilds) {
    const WalkTree tree = random_tree(200, 17);
    CutSettings settings;
    settings.criterion = CutCriterion::kBound;
    settings.error_ratio = 0.01;
    for (auto [representatives, search] : {std::pair{Representatives::kPixel, BoundSearch::kHeap},
                                           std::pair{Representatives::kPixel, BoundSearch::kWalk},
                                           std::pair{Representatives::kImportance, BoundSearch::kHeap},
                                           std::pair{Representatives::kImportance, BoundSearch::kWalk}}) {
        settings.representatives = representatives;
        settings.search = search;
        for (uint32_t pixel = 0; pixel < 20; ++pixel) {
            SurfacePoint p = test::surface({-3.0 + 0.3 * pixel, 0.0, 1.0 - 0.1 * pixel}, {0.0, 1.0, 0.0});
            p.pixel = {pixel, 2 * pixel};
            std::vector<CutNodeEstimate> nodes;
            const CutResult cut = search == BoundSearch::kHeap ? bound_heap_cut(tree, p, settings, &nodes)
                                                               : bound_walk_cut(tree, p, settings, &nodes);
            ASSERT_EQ(nodes.size(), cut.cut_size);
            glm::dvec3 afresh(0.0);
            for (const CutNodeEstimate& node : nodes) {
                const glm::dvec3 estimate = shade_cluster(tree, node.node, p, settings);
                test::expect_near_rel(node.estimate, estimate, 1e-12);
                afresh += estimate;
            }
            test::expect_near_rel(cut.radiance, afresh, 1e-9);
        }
    }
}

TEST(ImportanceRepresentative, TheClusterEstimateIsUnbiasedPerChannel) {
    const WalkTree tree = random_tree(32, 11);
    const SurfacePoint p = test::surface({0.5, 0.0, -0.5}, {0.0, 1.0, 0.0});
    CutSettings settings;
    settings.representatives = Representatives::kImportance;
    for (int32_t cluster : {0, 1, 2}) {
        SCOPED_TRACE(cluster);
        glm::dvec3 exact(0.0);
        for (int32_t leaf : leaves_under(tree, cluster)) exact += shade_node(tree, leaf, p);
        glm::dvec3 mean(0.0);
        const uint32_t side = 200;
        SurfacePoint q = p;
        for (q.pixel.y = 0; q.pixel.y < side; ++q.pixel.y)
            for (q.pixel.x = 0; q.pixel.x < side; ++q.pixel.x)
                mean += shade_cluster(tree, cluster, q, settings);
        mean /= double(side * side);
        // The leaf's own colour over its probability: unbiased channel by
        // channel, where the intensity draw is off by several per cent.
        test::expect_near_rel(mean, exact, 0.01);
    }
}

TEST(ImportanceRepresentative, TheEstimateStaysUnderTheClustersWeight) {
    // White unbounded points on a grey diffuse surface: f_r is albedo / pi in
    // every channel and each channel a third of the scalar intensity.
    std::mt19937_64 rng(31);
    std::vector<SceneLight> lights = test::random_lights_in_box(
        rng, 120, LightType::kPoint, {-4.0f, 1.0f, -4.0f}, {4.0f, 3.0f, 4.0f}, false);
    for (SceneLight& light : lights) light.color = glm::vec3(1.0f);
    const WalkTree tree = test::walk_tree(test::morton_pairing_tree(lights, 31));
    CutSettings settings;
    settings.representatives = Representatives::kImportance;
    const double f_r = 0.5 / test::kPi;
    int differs_from_tree = 0;
    for (uint32_t k = 0; k < 40; ++k) {
        SurfacePoint p =
            test::surface({-4.0 + 0.2 * k, 0.0, 3.0 - 0.15 * k}, {0.0, 1.0, 0.0}, {0.5, 0.5, 0.5});
        p.pixel = {k, 7 * k};
        for (int32_t i = 0; i < int32_t(tree.nodes.size()); ++i) {
            const GpuTreeNode& node = tree.node(i);
            int32_t children[2];
            // A parent weighs at least its children together: the premise of the bound.
            const auto geometry = [&](const GpuTreeNode& n) {
                return double(device::importance_geometry(n.bbox_min, n.bbox_max, glm::vec3(p.position),
                                                          glm::vec3(p.normal), false));
            };
            if (children_of(tree, i, children) == 2) {
                const double children_weight =
                    device::representative_scalar(tree.nodes[size_t(children[0])].intensity) *
                        geometry(tree.nodes[size_t(children[0])]) +
                    device::representative_scalar(tree.nodes[size_t(children[1])].intensity) *
                        geometry(tree.nodes[size_t(children[1])]);
                EXPECT_LE(children_weight,
                          device::representative_scalar(node.intensity) * geometry(node) * (1.0 + 1e-5));
            }
            const glm::dvec3 estimate = shade_cluster(tree, i, p, settings);
            const double bound = double(node.intensity.x) * geometry(node) * f_r;
            EXPECT_LE(estimate.x, bound * (1.0 + 1e-4)) << "node " << i;
            differs_from_tree += std::abs(estimate.x - shade_node(tree, i, p).x) > 1e-9 * bound;
        }
    }
    // Not the tree's estimate I_C f_rep under another name.
    EXPECT_GT(differs_from_tree, 100);
}

TEST(PixelRepresentative, TreeRepresentativesAreTheNodesOwn) {
    const WalkTree tree = random_tree(50, 23);
    SurfacePoint p = test::surface({1.0, 0.0, 0.0});
    p.pixel = {5, 9};
    const CutSettings settings;  // kTree
    for (int32_t i = 0; i < int32_t(tree.nodes.size()); ++i) {
        const glm::dvec3 own = shade_node(tree, i, p);
        const glm::dvec3 cluster = shade_cluster(tree, i, p, settings);
        EXPECT_EQ(own.x, cluster.x);
        EXPECT_EQ(own.y, cluster.y);
        EXPECT_EQ(own.z, cluster.z);
    }
}

TEST(PixelRepresentative, DrawsDependOnThePixelAndTheSeedOnly) {
    const WalkTree tree = random_tree(64, 29);
    CutSettings settings;
    settings.representatives = Representatives::kPixel;
    SurfacePoint a = test::surface({0.0, 0.0, 0.0});
    SurfacePoint b = a;
    a.pixel = {10, 20};
    b.pixel = {10, 20};
    EXPECT_EQ(pixel_representative_key(a, settings), pixel_representative_key(b, settings));
    // Over many pixels, seeds and neighbours draw different leaves from the root.
    int differ_by_pixel = 0, differ_by_seed = 0;
    CutSettings reseeded = settings;
    reseeded.representative_seed = 1;
    for (uint32_t x = 0; x < 100; ++x) {
        a.pixel = {x, 0};
        b.pixel = {x + 1, 0};
        const int32_t here = pixel_representative(tree, 0, pixel_representative_key(a, settings));
        differ_by_pixel += here != pixel_representative(tree, 0, pixel_representative_key(b, settings));
        differ_by_seed += here != pixel_representative(tree, 0, pixel_representative_key(a, reseeded));
    }
    EXPECT_GT(differ_by_pixel, 50);
    EXPECT_GT(differ_by_seed, 50);
}

}  // namespace
}  // namespace lc
