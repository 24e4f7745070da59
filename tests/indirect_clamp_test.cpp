// The paper's automatic clamping of indirect light (lightcuts/device/
// indirect_clamp.glsl.h): the formula against a brute-force fixed point, the
// CPU evaluator and every GPU lighting pass on a VPL 1 mm from a wall (no
// pixel above the clamp, no NaN), the GPU against the CPU on a clamped scene,
// and render --indirect off against a tree baked without indirect light.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include "editor_client/render/renderer.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/device/indirect_clamp.glsl.h"
#include "lightcuts/cuts/exact_indirect_clamp.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_records.h"
#include "render_test_support.h"

namespace lc {
namespace {

constexpr double kErrorRatio = 0.02;
constexpr double kRatio = 0.01;  // the clamp: half the error ratio

struct Clamped {
    glm::dvec3 total{0.0};    // before the clamp
    glm::dvec3 clamped{0.0};  // after
    device::IndirectSums sums = device::no_indirect_sums();
};

Clamped clamp_of(const glm::dvec3& others, const std::vector<glm::dvec3>& leaves) {
    Clamped c;
    c.total = others;
    device::add_cut_node(c.sums, false, false, others);
    for (const glm::dvec3& leaf : leaves) {
        device::add_cut_node(c.sums, true, true, leaf);
        c.total += leaf;
    }
    glm::dvec3 removed;
    c.clamped = device::indirect_clamped(c.total, c.sums, kRatio, removed);
    return c;
}

// The paper's clamp with every light clamped on its own: the largest t with
// t = ratio x (others + sum min(L_i, t)), by bisection (the right side minus t
// is positive below the fixed point and negative above it).
double ideal_clamped_total(double others, const std::vector<double>& leaves) {
    auto total_at = [&](double t) {
        double sum = others;
        for (double l : leaves) sum += std::min(l, t);
        return sum;
    };
    double lo = 0.0, hi = total_at(1e300);
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (kRatio * total_at(mid) > mid ? lo : hi) = mid;
    }
    return total_at(lo);
}

TEST(IndirectClampFormula, OneSpikeAddsAtMostTheRatioOfThePixel) {
    const glm::dvec3 others(1.0, 2.0, 3.0);
    const Clamped c = clamp_of(others, {glm::dvec3(1e6, 5e5, 1e-3)});
    for (int ch = 0; ch < 2; ++ch) {
        // The spike ends at ratio x the clamped total: others / (1 - ratio).
        EXPECT_NEAR(c.clamped[ch], others[ch] / (1.0 - kRatio), 1e-12 * others[ch]);
        EXPECT_LE(c.clamped[ch] - others[ch], kRatio * c.clamped[ch] * (1.0 + 1e-12));
    }
    EXPECT_EQ(c.clamped.z, c.total.z) << "a channel the spike does not dominate is left alone";
}

TEST(IndirectClampFormula, LightsUnderTheThresholdAreLeftExactlyAlone) {
    std::vector<glm::dvec3> leaves(300, glm::dvec3(1e-3, 2e-3, 5e-4));
    const Clamped c = clamp_of(glm::dvec3(1.0), leaves);
    EXPECT_EQ(c.clamped, c.total);
    const Clamped none = clamp_of(glm::dvec3(0.3, 0.2, 0.1), {});
    EXPECT_EQ(none.clamped, none.total);
    EXPECT_EQ(none.sums.leaves, 0u);
}

TEST(IndirectClampFormula, TwoSpikesMatchTheIdealClampAndMoreAreNeverUnderClamped) {
    std::mt19937_64 rng(16);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        const int spikes = 1 + trial % 12;
        std::vector<glm::dvec3> leaves;
        for (int i = 0; i < 40; ++i) leaves.push_back(glm::dvec3(1e-4 * unit(rng)));
        for (int i = 0; i < spikes; ++i) leaves.push_back(glm::dvec3(0.02 + 10.0 * unit(rng) * unit(rng)));
        std::shuffle(leaves.begin(), leaves.end(), rng);
        const double others = 0.5 + unit(rng);
        const Clamped c = clamp_of(glm::dvec3(others), leaves);
        std::vector<double> values;
        for (const glm::dvec3& l : leaves) values.push_back(l.x);
        const double ideal = ideal_clamped_total(others, values);
        ASSERT_TRUE(std::isfinite(c.clamped.x));
        EXPECT_GE(c.clamped.x, others * (1.0 - 1e-12));
        EXPECT_LE(c.clamped.x, c.total.x);
        if (spikes <= 2) {
            EXPECT_NEAR(c.clamped.x, ideal, 1e-9 * ideal) << "trial " << trial;
        } else {
            EXPECT_LE(c.clamped.x, ideal * (1.0 + 1e-9)) << "trial " << trial;
        }
        // No light, clamped, exceeds the threshold, which is ratio x the clamped total.
        const double t = device::indirect_clamp_threshold(c.sums.others.x, c.sums.largest.x, c.sums.second.x,
                                                          c.sums.rest.x, c.sums.rest_max, kRatio);
        EXPECT_LE(t, kRatio * c.clamped.x * (1.0 + 1e-9)) << "trial " << trial;
    }
}

// ---- the exact clamp (reference mode) -------------------------------------------

// Indirect light as a bake leaves it: many weak VPLs, a few spikes, sometimes nothing else.
std::vector<double> random_lights(std::mt19937_64& rng, int weak, int spikes) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> lights;
    for (int i = 0; i < weak; ++i) lights.push_back(1e-3 * unit(rng));
    for (int i = 0; i < spikes; ++i) lights.push_back(0.02 + 10.0 * unit(rng) * unit(rng));
    std::shuffle(lights.begin(), lights.end(), rng);
    return lights;
}

TEST(ExactClamp, EveryLightAtMostTheThresholdWhichIsTheRatioOfTheClampedTotal) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int trial = 0; trial < 300; ++trial) {
        const std::vector<double> lights = random_lights(rng, 10 + trial % 7 * 60, trial % 13);
        // Every third pixel is lit by indirect light only.
        const double others = trial % 3 == 0 ? 0.0 : 0.05 * unit(rng);
        const double t = exact_clamp_threshold(others, lights, kRatio);
        const double ideal = ideal_clamped_total(others, lights);
        double clamped = others;
        for (double l : lights) clamped += std::min(l, t);
        EXPECT_NEAR(clamped, ideal, 1e-9 * ideal + 1e-300) << "trial " << trial;
        EXPECT_NEAR(t, kRatio * clamped, 1e-12 * clamped) << "trial " << trial;
    }
}

// What the cut's two-largest approximation cannot do: a pixel lit by 300
// weak VPLs (0.1) and three bright ones (500, 5, 5), with no other light.
// The approximation's rest over its largest light is 35 / 5, far under
// 1 / ratio - 2, so it keeps only t = 0 and removes all of it; the exact
// clamp holds the bright ones at t and keeps the weak ones.
TEST(ExactClamp, AnIndirectOnlyPixelKeepsItsLightWhereTheApproximationZeroesIt) {
    std::vector<glm::dvec3> lights(300, glm::dvec3(0.1));
    for (double bright : {500.0, 5.0, 5.0}) lights.push_back(glm::dvec3(bright));
    const Clamped approximated = clamp_of(glm::dvec3(0.0), lights);
    EXPECT_EQ(approximated.clamped.x, 0.0);
    const ExactClamp exact = exact_indirect_clamp(glm::dvec3(0.0), lights, kRatio);
    // t = ratio (300 x 0.1 + 3 t).
    const double t = kRatio * 30.0 / (1.0 - 3.0 * kRatio);
    EXPECT_NEAR(exact.threshold.x, t, 1e-12);
    EXPECT_NEAR(exact.radiance.x, 30.0 + 3.0 * t, 1e-9);
    EXPECT_NEAR(exact.removed.x, 540.0 - exact.radiance.x, 1e-9);
    // Fewer comparable lights than 1 / ratio and nothing else: no positive root.
    const std::vector<double> few(60, 1.0);
    EXPECT_EQ(exact_clamp_threshold(0.0, few, kRatio), 0.0);
}

// The GPU reference's passes (device::exact_clamp_start, tally_exact_clamp,
// exact_clamp_step), run on the CPU: never under the root, and on it within
// the passes the reference runs.
TEST(ExactClamp, NewtonsPassesComeDownOnTheRootWithoutPassingIt) {
    std::mt19937_64 rng(18);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    uint32_t most_passes = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const std::vector<double> lights = random_lights(rng, 10 + trial % 7 * 60, trial % 13);
        const double others = trial % 3 == 0 ? 0.0 : 0.05 * unit(rng);
        const double root = exact_clamp_threshold(others, lights, kRatio);
        device::IndirectSums sums = device::no_indirect_sums();
        for (double l : lights) device::add_indirect_leaf(sums, glm::dvec3(l));
        double t = device::exact_clamp_start(others, sums.largest.x, sums.second.x, sums.rest.x, kRatio);
        // The GPU's last pass takes the step and clamps with the tally it
        // made, exact once the step lands on the root.
        uint32_t passes = 0;
        while (std::abs(t - root) > 1e-12 * root && passes < 64) {
            glm::dvec3 below(0.0), above(0.0);
            for (double l : lights) device::tally_exact_clamp(below, above, glm::dvec3(l), glm::dvec3(t));
            const double next = device::exact_clamp_step(others, below.x, above.x, t, kRatio);
            ASSERT_GE(next, root * (1.0 - 1e-12)) << "trial " << trial << ", pass " << passes;
            t = next;
            ++passes;
        }
        EXPECT_NEAR(t, root, 1e-12 * root + 1e-300) << "trial " << trial;
        most_passes = std::max(most_passes, passes);
    }
    std::printf("  passes to the root: at most %u\n", most_passes);
    EXPECT_LE(most_passes, device::kExactClampPasses);
}

// ---- the tree and the CPU evaluator ------------------------------------------

// Direct light in the floor scene (render_test_support.h), a VPL 1 mm in front
// of the back wall (z = -5) facing it, and, with `bounced`, 300 dim VPLs on
// the floor: the indirect lights of a bake.
std::vector<SceneLight> direct_lights() {
    std::vector<SceneLight> lights = {
        test::point_light({-1.0f, 3.0f, -2.0f}, {1.0f, 0.9f, 0.8f}, 12.0f),
        test::point_light({1.5f, 2.0f, -3.5f}, {0.6f, 0.7f, 1.0f}, 6.0f),
        test::spot_light({0.0f, 4.0f, -3.0f}, {0.0f, -1.0f, -0.3f}, {1.0f, 1.0f, 0.9f}, 20.0f, 0.2f, 0.6f),
    };
    for (uint32_t i = 0; i < lights.size(); ++i) test::set_unit_guid(lights[i], i);
    return lights;
}

constexpr glm::vec3 kSpikePosition{0.1f, 1.0f, -5.0f + 0.001f};

std::vector<SceneLight> lights_with_indirect(bool bounced) {
    std::vector<SceneLight> lights = direct_lights();
    SceneLight spike = test::oriented_light(kSpikePosition, {0.0f, 0.0f, -1.0f}, {1.0f, 0.8f, 0.6f}, 2.0f);
    spike.indirect = true;
    test::set_unit_guid(spike, 100);
    lights.push_back(spike);
    if (bounced) {
        std::mt19937_64 rng(7);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (uint32_t i = 0; i < 300; ++i) {
            SceneLight vpl = test::oriented_light({-4.0f + 8.0f * u(rng), 0.0f, -4.9f + 9.0f * u(rng)},
                                                  {0.0f, 1.0f, 0.0f}, {0.8f, 0.7f, 0.6f}, 0.01f * u(rng));
            vpl.indirect = true;
            test::set_unit_guid(vpl, 200 + i);
            lights.push_back(vpl);
        }
    }
    return lights;
}

// The spike made a radiosity patch, a disk of kPatchRadius, with 20 more
// patches on the back wall; with `vpls`, the 300 floor VPLs stay VPLs.
constexpr float kPatchRadius = 0.05f;

std::vector<SceneLight> lights_with_patches(bool vpls) {
    std::vector<SceneLight> lights = lights_with_indirect(vpls);
    SceneLight& spike = lights[direct_lights().size()];
    spike.patch = true;
    spike.source_radius = kPatchRadius;
    for (uint32_t i = 0; i < 20; ++i) {
        SceneLight patch = test::oriented_light({-2.0f + 0.2f * float(i), 0.5f + 0.1f * float(i % 3), -4.99f},
                                                {0.0f, 0.0f, 1.0f}, {0.9f, 0.5f, 0.4f}, 0.05f);
        patch.indirect = patch.patch = true;
        patch.source_radius = kPatchRadius;
        test::set_unit_guid(patch, 600 + i);
        lights.push_back(patch);
    }
    return lights;
}

LightTree build(const std::vector<SceneLight>& lights) {
    Result<bake::BuildResult> built = bake::build_light_tree(lights, bake::BuildOptions{}, nullptr);
    EXPECT_TRUE(built.ok()) << built.error();
    return built.ok() ? built->tree : LightTree{};
}

TEST(IndirectTree, IndirectLightsHaveSubtreesOfTheirOwnAndTravelOnTheWire) {
    const LightTree tree = build(lights_with_indirect(true));
    ASSERT_TRUE(validate_tree(tree).ok()) << validate_tree(tree).error();
    size_t indirect_leaves = 0, indirect_clusters = 0;
    for (const LightTreeNode& node : tree.nodes) {
        if (node.is_leaf()) {
            indirect_leaves += node.flags.indirect();
            continue;
        }
        const bool both =
            tree.nodes[size_t(node.left)].flags.indirect() && tree.nodes[size_t(node.right)].flags.indirect();
        EXPECT_EQ(node.flags.indirect(), both);
        // Only junctions join indirect with direct light: no cluster mixes them.
        if (!node.flags.mixed_types()) {
            EXPECT_EQ(node.flags.indirect(), tree.nodes[size_t(node.left)].flags.indirect());
        }
        indirect_clusters += node.flags.indirect();
    }
    EXPECT_EQ(indirect_leaves, 301u);
    EXPECT_EQ(indirect_clusters, 300u);

    Result<LightTree> decoded = decode_result_channel(encode_result_channel(tree));
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    for (size_t i = 0; i < tree.nodes.size(); ++i)
        EXPECT_EQ(decoded->nodes[i].flags.indirect(), tree.nodes[i].flags.indirect());

    // A cluster that calls itself indirect over a direct child is refused.
    LightTree bad = tree;
    for (LightTreeNode& node : bad.nodes) {
        if (node.flags.mixed_types()) {
            node.flags.set(kNodeIndirect, true);
            break;
        }
    }
    EXPECT_FALSE(decode_result_channel(encode_result_channel(bad)).ok());
}

TEST(IndirectTree, TreesWithoutIndirectLightsKeepTheirBytes) {
    const LightTree tree = build(direct_lights());
    for (const LightTreeNode& node : tree.nodes) EXPECT_FALSE(node.flags.indirect());
    const std::vector<uint8_t> bytes = encode_result_channel(tree);
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        uint32_t flags = 0;
        std::memcpy(&flags, bytes.data() + 4 + i * result_record_bytes() + 16, sizeof flags);
        EXPECT_EQ(flags & 2u, 0u) << "node " << i;
    }
}

TEST(IndirectTree, PatchesHaveSubtreesApartFromVplsAndTravelOnTheWire) {
    const LightTree tree = build(lights_with_patches(true));
    ASSERT_TRUE(validate_tree(tree).ok()) << validate_tree(tree).error();
    size_t patch_leaves = 0, vpl_leaves = 0;
    for (const LightTreeNode& node : tree.nodes) {
        EXPECT_TRUE(!node.flags.patch() || node.flags.indirect());
        EXPECT_EQ(node.source_radius, node.flags.patch() ? kPatchRadius : 0.0f);
        if (node.is_leaf()) {
            patch_leaves += node.flags.patch();
            vpl_leaves += node.flags.indirect() && !node.flags.patch();
            continue;
        }
        // Only junctions join patches with other lights: no cluster mixes them.
        if (!node.flags.mixed_types()) {
            EXPECT_EQ(node.flags.patch(), tree.nodes[size_t(node.left)].flags.patch());
        }
        EXPECT_EQ(node.flags.patch(), tree.nodes[size_t(node.left)].flags.patch() &&
                                          tree.nodes[size_t(node.right)].flags.patch());
    }
    EXPECT_EQ(patch_leaves, 21u);
    EXPECT_EQ(vpl_leaves, 300u);

    Result<LightTree> decoded = decode_result_channel(encode_result_channel(tree));
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        EXPECT_EQ(decoded->nodes[i].flags.patch(), tree.nodes[i].flags.patch());
        EXPECT_EQ(decoded->nodes[i].source_radius, tree.nodes[i].source_radius);
    }

    // Refused: a cluster of VPLs that calls itself a patch, a patch that is
    // not indirect, a source radius on a light that is no patch.
    const auto refused = [&](const std::function<void(LightTree&)>& spoil) {
        LightTree bad = tree;
        spoil(bad);
        return !decode_result_channel(encode_result_channel(bad)).ok();
    };
    const auto first = [](LightTree& t,
                          const std::function<bool(const LightTreeNode&)>& which) -> LightTreeNode& {
        return *std::find_if(t.nodes.begin(), t.nodes.end(), which);
    };
    EXPECT_TRUE(refused([&](LightTree& t) {
        first(t, [](const LightTreeNode& n) {
            return !n.is_leaf() && n.flags.indirect() && !n.flags.patch();
        }).flags.set(kNodePatch, true);
    }));
    EXPECT_TRUE(refused([&](LightTree& t) {
        first(t, [](const LightTreeNode& n) { return n.flags.patch(); }).flags.set(kNodeIndirect, false);
    }));
    EXPECT_TRUE(refused([&](LightTree& t) {
        first(t, [](const LightTreeNode& n) {
            return n.flags.indirect() && !n.flags.patch();
        }).source_radius = 0.1f;
    }));

    // The builder refuses the same lights.
    std::vector<SceneLight> lights = lights_with_patches(false);
    lights.back().indirect = false;
    EXPECT_FALSE(bake::build_light_tree(lights, bake::BuildOptions{}, nullptr).ok());
}

// Points on the wall near the spike and on the floor: the spike dominates the first.
std::vector<SurfacePoint> wall_and_floor_points() {
    std::vector<SurfacePoint> points;
    for (double dx : {0.0, 0.001, 0.003, 0.01, 0.03, 0.1, 0.5}) {
        SurfacePoint p;
        p.position = {0.1 + dx, 1.0 + 0.5 * dx, -5.0};
        p.normal = {0.0, 0.0, 1.0};
        p.albedo = {0.3, 0.5, 0.9};
        points.push_back(p);
    }
    for (double x : {-2.0, 0.0, 2.0}) {
        SurfacePoint p;
        p.position = {x, 0.0, -4.0};
        p.normal = {0.0, 1.0, 0.0};
        p.albedo = {0.8, 0.7, 0.6};
        points.push_back(p);
    }
    return points;
}

std::vector<CutSettings> every_search() {
    CutSettings radius;
    CutSettings walk;
    walk.criterion = CutCriterion::kBound;
    walk.error_ratio = kErrorRatio;
    CutSettings heap = walk;
    heap.search = BoundSearch::kHeap;
    return {radius, walk, heap};
}

TEST(IndirectClampCpu, AVplOneMillimetreFromAWallAddsAtMostTheRatio) {
    const WalkTree tree = test::walk_tree(build(lights_with_indirect(false)));
    for (CutSettings settings : every_search()) {
        // The bound searches' cuts of the direct light may differ by the error
        // ratio between the two (the spike, clamped, still raises the total).
        const double margin = settings.criterion == CutCriterion::kBound ? 2.0 * kErrorRatio : 1e-9;
        for (const SurfacePoint& p : wall_and_floor_points()) {
            const CutResult on = shade_lightcuts(tree, {}, p, settings);
            settings.indirect = false;
            const CutResult off = shade_lightcuts(tree, {}, p, settings);
            settings.indirect = true;
            for (int ch = 0; ch < 3; ++ch) {
                ASSERT_TRUE(std::isfinite(on.radiance[ch]));
                // The spike is the only indirect light: what it adds is at most
                // ratio x the pixel, so the pixel at most the rest / (1 - ratio).
                EXPECT_LE(on.radiance[ch], off.radiance[ch] / (1.0 - kRatio) * (1.0 + margin) + 1e-300);
                EXPECT_GE(on.radiance[ch], off.radiance[ch] * (1.0 - margin));
            }
        }
        const CutResult at_spike = shade_lightcuts(tree, {}, wall_and_floor_points()[0], settings);
        EXPECT_GT(device::largest_channel(at_spike.clamped), 1e3) << "the spike was not clamped";
        EXPECT_GT(device::largest_channel(at_spike.indirect), device::largest_channel(at_spike.clamped));
    }
}

// The same spike as a patch: the disk's 1 / (d^2 + r^2) instead of a clamp.
TEST(IndirectClampCpu, APatchOneMillimetreFromAWallIsADiskNotASpike) {
    const WalkTree tree = test::walk_tree(build(lights_with_patches(false)));
    const SceneLight spike = lights_with_patches(false)[direct_lights().size()];
    CutSettings exhaustive;  // the radius criterion refines every cluster of unbounded lights
    for (const SurfacePoint& p : wall_and_floor_points()) {
        const CutResult on = shade_lightcuts(tree, {}, p, exhaustive);
        EXPECT_EQ(on.clamped, glm::dvec3(0.0));
        for (int ch = 0; ch < 3; ++ch) ASSERT_TRUE(std::isfinite(on.radiance[ch]));
    }
    // Under the patch's centre both cosines are 1: f_r I / (d^2 + r^2), Lambert's f_r = albedo / pi.
    const SurfacePoint under = wall_and_floor_points()[0];
    CutSettings off = exhaustive;
    off.indirect = false;
    const glm::dvec3 patch = shade_lightcuts(tree, {}, under, exhaustive).radiance -
                             shade_lightcuts(tree, {}, under, off).radiance;
    const double d = 0.001, r = kPatchRadius;
    const glm::dvec3 disk =
        under.albedo / std::numbers::pi * glm::dvec3(spike.color) * double(spike.intensity) / (d * d + r * r);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(patch[ch], disk[ch], 1e-4 * disk[ch]) << "channel " << ch;

    for (CutSettings settings : every_search()) {
        const CutResult at_spike = shade_lightcuts(tree, {}, under, settings);
        EXPECT_EQ(at_spike.clamped, glm::dvec3(0.0));
        EXPECT_GT(device::largest_channel(at_spike.indirect), 0.0);
    }
}

TEST(IndirectClampCpu, IndirectOffEqualsATreeWithoutIndirectLights) {
    const WalkTree with = test::walk_tree(build(lights_with_indirect(true)));
    const WalkTree without = test::walk_tree(build(direct_lights()));
    for (CutSettings settings : every_search()) {
        settings.indirect = false;
        for (const SurfacePoint& p : wall_and_floor_points()) {
            const glm::dvec3 a = shade_lightcuts(with, {}, p, settings).radiance;
            const glm::dvec3 b = shade_lightcuts(without, {}, p, settings).radiance;
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(a[ch], b[ch], 1e-12 * std::abs(b[ch]));
        }
    }
}

// ---- the GPU passes ---------------------------------------------------------

constexpr uint32_t kSize = 48;

class IndirectClampGpu : public test::VulkanTest {
protected:
    void SetUp() override {
        test::VulkanTest::SetUp();
        if (IsSkipped()) return;
        scene_ = test::make_floor_scene();
        settings_.width = settings_.height = kSize;
        // Close to the wall, so that pixels fall within centimetres of the spike.
        settings_.camera.eye = {0.1f, 1.0f, -3.5f};
        settings_.camera.target = {0.1f, 0.9f, -5.0f};
        settings_.camera.yfov = 0.9f;
        settings_.error_ratio = float(kErrorRatio);
    }

    std::unique_ptr<client::Renderer> renderer(const WalkTree& tree, bool indirect = true) {
        client::RendererOptions options;
        options.indirect = indirect;
        Result<std::unique_ptr<client::Renderer>> r = client::Renderer::create(*context_, scene_, &tree, options);
        EXPECT_TRUE(r.ok()) << r.error();
        return r.ok() ? std::move(r).value() : nullptr;
    }

    struct Frame {
        client::RenderStats stats;
        std::vector<float> hdr;
        client::GBufferReadback gbuffer;
    };

    Frame render(client::Renderer& r, client::RenderMode mode, CutCriterion criterion,
                 BoundSearch search = BoundSearch::kWalk) {
        client::RenderSettings s = settings_;
        s.mode = mode;
        s.criterion = criterion;
        s.bound_search = search;
        Frame f;
        Result<client::RenderStats> stats = r.render(s);
        EXPECT_TRUE(stats.ok()) << stats.error();
        if (!stats.ok()) return f;
        f.stats = *stats;
        f.hdr = r.read_hdr().value();
        f.gbuffer = r.read_gbuffer().value();
        return f;
    }

    struct Mode {
        client::RenderMode mode;
        CutCriterion criterion;
        BoundSearch search;
        const char* name;
    };
    static std::vector<Mode> every_mode() {
        return {{client::RenderMode::kReference, CutCriterion::kRadius, BoundSearch::kWalk, "reference"},
                {client::RenderMode::kLightcuts, CutCriterion::kRadius, BoundSearch::kWalk, "radius"},
                {client::RenderMode::kLightcuts, CutCriterion::kBound, BoundSearch::kWalk, "bound walk"},
                {client::RenderMode::kLightcuts, CutCriterion::kBound, BoundSearch::kHeap, "bound heap"}};
    }

    // Every pixel of every mode against the CPU evaluator: radiance, clamped and indirect energy.
    void expect_gpu_shades_like_the_cpu(const WalkTree& tree);

    Scene scene_;
    client::RenderSettings settings_;
};

TEST_F(IndirectClampGpu, AVplOneMillimetreFromAWallAddsAtMostTheRatioInEveryMode) {
    const WalkTree tree = test::walk_tree(build(lights_with_indirect(false)));
    std::unique_ptr<client::Renderer> on = renderer(tree, true);
    std::unique_ptr<client::Renderer> off = renderer(tree, false);
    ASSERT_TRUE(on && off);
    for (const Mode& m : every_mode()) {
        const Frame a = render(*on, m.mode, m.criterion, m.search);
        const Frame b = render(*off, m.mode, m.criterion, m.search);
        ASSERT_EQ(a.hdr.size(), b.hdr.size());
        EXPECT_EQ(a.stats.nonfinite_pixels, 0u) << m.name;
        EXPECT_EQ(a.stats.indirect.mode, "on");
        EXPECT_EQ(b.stats.indirect.mode, "off");
        EXPECT_GT(a.stats.indirect.clamped_energy, 0.0) << m.name << ": the spike was not clamped";
        EXPECT_GT(a.stats.indirect.clamped_fraction(), 0.5) << m.name;
        EXPECT_LE(a.stats.indirect.clamped_fraction(), 1.0) << m.name;
        size_t geometry = 0;
        for (size_t i = 0; i < a.hdr.size(); i += 4) {
            if (a.gbuffer.position[i + 3] == 0.0f) continue;
            ++geometry;
            for (int ch = 0; ch < 3; ++ch) {
                ASSERT_TRUE(std::isfinite(a.hdr[i + ch]));
                EXPECT_LE(a.hdr[i + ch], b.hdr[i + ch] / (1.0f - float(kRatio)) * (1.0f + 1e-4f) + 1e-7f)
                    << m.name << ", pixel " << i / 4 << " channel " << ch;
            }
        }
        EXPECT_GT(geometry, size_t(kSize) * kSize / 2) << m.name;
    }
}

void IndirectClampGpu::expect_gpu_shades_like_the_cpu(const WalkTree& tree) {
    std::unique_ptr<client::Renderer> r = renderer(tree);
    ASSERT_TRUE(r);
    for (const Mode& m : every_mode()) {
        const Frame f = render(*r, m.mode, m.criterion, m.search);
        CutSettings cpu_settings;
        cpu_settings.criterion = m.criterion;
        cpu_settings.search = m.search;
        cpu_settings.error_ratio = kErrorRatio;
        size_t compared = 0, within = 0;
        double clamped_cpu = 0.0, indirect_cpu = 0.0;
        for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
            if (f.gbuffer.position[4 * i + 3] == 0.0f) continue;
            const SurfacePoint p = test::gbuffer_point(f.gbuffer, i);
            // Reference mode: every leaf, its VPLs clamped exactly.
            const CutResult cpu = m.mode == client::RenderMode::kReference
                                      ? shade_tree_reference(tree, {}, p, cpu_settings)
                                      : shade_lightcuts(tree, {}, p, cpu_settings);
            clamped_cpu += cpu.clamped.x + cpu.clamped.y + cpu.clamped.z;
            indirect_cpu += cpu.indirect.x + cpu.indirect.y + cpu.indirect.z;
            ++compared;
            bool close = true;
            for (int ch = 0; ch < 3; ++ch) {
                const double err = std::abs(double(f.hdr[4 * i + ch]) - cpu.radiance[ch]);
                close = close && err <= 1e-3 * std::abs(cpu.radiance[ch]) + 1e-7;
            }
            within += close;
        }
        ASSERT_GT(compared, 0u);
        std::printf("  %s: %zu of %zu pixels within 1e-3, clamped energy GPU %.4g CPU %.4g, passes %u (change %.3g)\n",
                    m.name, within, compared, f.stats.indirect.clamped_energy, clamped_cpu, f.stats.indirect.reference_clamp_passes,
                    f.stats.indirect.reference_clamp_change);
        // The bound searches may choose another cut where float and double
        // straddle a threshold; the exhaustive cuts may not.
        const bool exhaustive = m.criterion == CutCriterion::kRadius;
        EXPECT_GE(double(within), (exhaustive ? 1.0 : 0.97) * double(compared)) << m.name;
        EXPECT_NEAR(f.stats.indirect.clamped_energy, clamped_cpu, (exhaustive ? 1e-2 : 0.05) * clamped_cpu) << m.name;
        EXPECT_NEAR(f.stats.indirect.energy, indirect_cpu, (exhaustive ? 1e-2 : 0.05) * indirect_cpu) << m.name;
        EXPECT_EQ(f.stats.nonfinite_pixels, 0u) << m.name;
    }
}

TEST_F(IndirectClampGpu, TheGpuClampsLikeTheCpu) {
    expect_gpu_shades_like_the_cpu(test::walk_tree(build(lights_with_indirect(true))));
}

// Every pixel lit by VPLs only: a spike 1 mm from the wall and 300 weak VPLs.
// The reference's exact clamp keeps the light the approximation removed.
TEST_F(IndirectClampGpu, TheReferenceClampsIndirectOnlyPixelsExactly) {
    std::vector<SceneLight> lights = lights_with_indirect(true);
    lights.erase(lights.begin(), lights.begin() + std::ptrdiff_t(direct_lights().size()));
    const WalkTree tree = test::walk_tree(build(lights));
    std::unique_ptr<client::Renderer> r = renderer(tree);
    ASSERT_TRUE(r);
    const Frame f = render(*r, client::RenderMode::kReference, CutCriterion::kRadius);
    EXPECT_EQ(f.stats.indirect.reference_clamp_passes, device::kExactClampPasses);
    CutSettings settings;
    settings.error_ratio = kErrorRatio;
    size_t compared = 0, within = 0, zeroed_by_the_approximation = 0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
        if (f.gbuffer.position[4 * i + 3] == 0.0f) continue;
        const SurfacePoint p = test::gbuffer_point(f.gbuffer, i);
        const CutResult exact = shade_tree_reference(tree, {}, p, settings);
        const CutResult approximated = shade_lightcuts(tree, {}, p, settings);  // every leaf on the cut
        zeroed_by_the_approximation += approximated.radiance.x == 0.0 && exact.radiance.x > 0.0;
        ++compared;
        bool close = true;
        for (int ch = 0; ch < 3; ++ch)
            close = close && std::abs(double(f.hdr[4 * i + ch]) - exact.radiance[ch]) <=
                                 1e-3 * std::abs(exact.radiance[ch]) + 1e-7;
        within += close;
    }
    std::printf("  %zu of %zu pixels within 1e-3; %zu the approximation zeroed; change %.3g\n", within, compared,
                zeroed_by_the_approximation, f.stats.indirect.reference_clamp_change);
    EXPECT_GT(zeroed_by_the_approximation, compared / 10) << "the scene does not test the exact clamp";
    EXPECT_EQ(within, compared);
    EXPECT_EQ(f.stats.nonfinite_pixels, 0u);
}

// Patches (disks, not clamped) beside clamped VPLs, in every mode.
TEST_F(IndirectClampGpu, TheGpuShadesPatchesLikeTheCpu) {
    expect_gpu_shades_like_the_cpu(test::walk_tree(build(lights_with_patches(true))));
}

// The clamp's sums ride in the walk states from dispatch to dispatch: a
// reference split over submissions (every dispatch its own: this small
// image's leaves in layers of workgroups, then their sum) keeps them.
TEST_F(IndirectClampGpu, AClampedReferenceOverSeveralSubmissionsIsTheSameFrame) {
    const WalkTree tree = test::walk_tree(build(lights_with_indirect(true)));
    settings_.width = settings_.height = 16;
    std::unique_ptr<client::Renderer> whole = renderer(tree);
    client::RendererOptions split_options;
    split_options.reference_evaluations_per_submission = 1;
    Result<std::unique_ptr<client::Renderer>> split =
        client::Renderer::create(*context_, scene_, &tree, split_options);
    ASSERT_TRUE(whole && split.ok());
    const Frame one = render(*whole, client::RenderMode::kReference, CutCriterion::kRadius);
    const Frame several = render(**split, client::RenderMode::kReference, CutCriterion::kRadius);
    EXPECT_EQ(one.stats.timing.submissions, 1u);
    EXPECT_GT(several.stats.timing.submissions, 1u);
    EXPECT_EQ(one.hdr, several.hdr);
    EXPECT_EQ(one.stats.indirect.clamped_energy, several.stats.indirect.clamped_energy);
    EXPECT_GT(several.stats.indirect.clamped_energy, 0.0);
}

// Newton's passes read the visibility the sums' pass kept (one bit per pixel
// and leaf) instead of tracing each VPL's shadow ray again: the same frame,
// bit for bit, with the VPLs' rays traced once; over budget they trace again.
TEST_F(IndirectClampGpu, TheReferenceTracesEachVplsShadowRayOnce) {
    const WalkTree tree = test::walk_tree(build(lights_with_indirect(true)));
    std::unique_ptr<client::Renderer> kept = renderer(tree);
    client::RendererOptions no_budget;
    no_budget.vpl_visibility_budget_bytes = 0;
    Result<std::unique_ptr<client::Renderer>> traced = client::Renderer::create(*context_, scene_, &tree, no_budget);
    ASSERT_TRUE(kept && traced.ok());
    const Frame a = render(*kept, client::RenderMode::kReference, CutCriterion::kRadius);
    const Frame b = render(**traced, client::RenderMode::kReference, CutCriterion::kRadius);
    ASSERT_GT(a.stats.indirect.reference_clamp_passes, 0u);
    ASSERT_GT(a.stats.shadows.rays, 0u) << "the scene casts no shadows: nothing to keep";
    EXPECT_TRUE(a.stats.indirect.reference_visibility_kept);
    EXPECT_FALSE(b.stats.indirect.reference_visibility_kept);
    EXPECT_EQ(a.hdr, b.hdr);
    EXPECT_EQ(a.stats.indirect.clamped_energy, b.stats.indirect.clamped_energy);
    // Newton's passes traced again every VPL ray the sums' pass traced.
    std::printf("  shadow rays: %llu kept, %llu traced again\n", (unsigned long long)a.stats.shadows.rays,
                (unsigned long long)b.stats.shadows.rays);
    EXPECT_LT(a.stats.shadows.rays, b.stats.shadows.rays);
    EXPECT_GE(b.stats.shadows.rays - a.stats.shadows.rays, uint64_t(device::kExactClampPasses));
}

TEST_F(IndirectClampGpu, IndirectOffEqualsATreeBakedWithoutIndirectLight) {
    const WalkTree with = test::walk_tree(build(lights_with_indirect(true)));
    const WalkTree without = test::walk_tree(build(direct_lights()));
    std::unique_ptr<client::Renderer> off = renderer(with, false);
    std::unique_ptr<client::Renderer> direct = renderer(without);
    ASSERT_TRUE(off && direct);
    for (const Mode& m : every_mode()) {
        const Frame a = render(*off, m.mode, m.criterion, m.search);
        const Frame b = render(*direct, m.mode, m.criterion, m.search);
        ASSERT_EQ(a.hdr.size(), b.hdr.size());
        EXPECT_TRUE(b.stats.indirect.mode.empty());
        for (size_t i = 0; i < a.hdr.size(); ++i)
            EXPECT_NEAR(a.hdr[i], b.hdr[i], 1e-5f * std::abs(b.hdr[i]) + 1e-9f) << m.name << ", value " << i;
    }
}

}  // namespace
}  // namespace lc
