// The estimate a bake is admitted by (issue 27): each heavy part of the
// table's rows counted from the request, before anything runs.
#include "lightmass_server/bake/bake_footprint.h"

#include <gtest/gtest.h>

#include <memory>

#include "indirect_scenes.h"
#include "protocol/bake_limits.h"

namespace lc::bake {
namespace {

constexpr uint64_t kMiB = uint64_t{1} << 20;

BakeInputs with_lights(size_t count) {
    BakeInputs inputs;
    inputs.lights = std::make_shared<const std::vector<SceneLight>>(count);
    return inputs;
}

TEST(BakeFootprint, TreeLightsCostTheirBytesEach) {
    // 1,000 lights: one level under the exact pairing limit, so every node is paired exactly too.
    const BakeFootprint footprint = estimate_bake_footprint(with_lights(1000), false);
    EXPECT_EQ(footprint.tree_lights, 1000u);
    EXPECT_EQ(footprint.bytes, kBakeFixedBytes + 1000 * (kTreeBytesPerLight + kExactPairingBytesPerNode));
    EXPECT_GT(estimate_bake_footprint(with_lights(1000), true).bytes, footprint.bytes);  // a recorded result
}

TEST(BakeFootprint, ExactPairingCountsTheLargestLevelItPairsExactly) {
    const uint64_t lights = 100000;
    BakeInputs inputs = with_lights(lights);
    const uint64_t tree = kBakeFixedBytes + lights * kTreeBytesPerLight;
    // Auto: levels above the limit are paired approximately; the largest exact one has 32,768 nodes.
    EXPECT_EQ(estimate_bake_footprint(inputs, false).bytes,
              tree + uint64_t{kDefaultExactPairingLimit} * kExactPairingBytesPerNode);
    inputs.build.exact_pairing_limit = 50000;
    EXPECT_EQ(estimate_bake_footprint(inputs, false).bytes, tree + 50000 * kExactPairingBytesPerNode);
    inputs.build.pairing = PairingMode::kExact;  // every level, the first one of 100,000 nodes included
    EXPECT_EQ(estimate_bake_footprint(inputs, false).bytes, tree + lights * kExactPairingBytesPerNode);
    inputs.build.pairing = PairingMode::kApproximate;
    EXPECT_EQ(estimate_bake_footprint(inputs, false).bytes, tree);
    // The other builders never run the matching; the agglomerative one holds more per light.
    inputs.build.pairing = PairingMode::kExact;
    inputs.build.builder = BuilderKind::kLbvh;
    EXPECT_EQ(estimate_bake_footprint(inputs, false).bytes, tree);
    inputs.build.builder = BuilderKind::kAgglomerative;
    EXPECT_EQ(estimate_bake_footprint(inputs, false).bytes,
              kBakeFixedBytes + lights * kAgglomerativeTreeBytesPerLight);
}

// The calibration's measured peaks (docs/bench/bake_footprint.csv, the server's
// VmHWM less its RSS before the bake, run to the end): the estimate stays above
// each, and within a third of it, so bakes that fit are not refused.
TEST(BakeFootprint, EstimatesBoundTheMeasuredPeaksClosely) {
    struct Measured {
        BuilderKind builder;
        uint64_t lights;
        uint64_t peak_mib;  // less the stored scene channel's reservation, which is counted apart
    };
    for (const Measured& m :
         {Measured{BuilderKind::kOptimalPair, 1048576, 562}, Measured{BuilderKind::kLbvh, 1048576, 553},
          Measured{BuilderKind::kAgglomerative, 1048576, 594},
          Measured{BuilderKind::kOptimalPair, 262144, 143}, Measured{BuilderKind::kOptimalPair, 65536, 58}}) {
        BakeInputs inputs = with_lights(m.lights);
        inputs.build.builder = m.builder;
        const uint64_t estimate = estimate_bake_footprint(inputs, false).bytes;
        EXPECT_GE(estimate, m.peak_mib * kMiB) << m.lights << " lights, builder " << int(m.builder);
        EXPECT_LE(estimate, m.peak_mib * kMiB * 4 / 3) << m.lights << " lights, builder " << int(m.builder);
    }
}

TEST(BakeFootprint, AnEnvironmentMapCountsItsSamplersTable) {
    // 8192 x 4096: the summed-area table alone is 770 MiB, beyond a 512 MiB budget.
    BakeInputs inputs = with_lights(0);
    auto environment = std::make_shared<Environment>();
    environment->map.width = 8192;
    environment->map.height = 4096;
    inputs.environment = environment;
    const BakeFootprint footprint = estimate_bake_footprint(inputs, false);
    EXPECT_GT(footprint.bytes, 768 * kMiB);
    EXPECT_EQ(footprint.tree_lights, kDefaultEnvironmentLights);
    EXPECT_EQ(footprint.largest, "the environment sampler's table");
}

TEST(BakeFootprint, AreaLightSamplesCountOnlyWhenATriangleEmits) {
    BakeInputs inputs = with_lights(0);
    inputs.area_lights = kMaxAreaLights;
    inputs.geometry =
        std::make_shared<const SceneGeometry>(test::closed_box({glm::vec3(0.5f), glm::vec3(0.0f)}));
    EXPECT_EQ(estimate_bake_footprint(inputs, false).tree_lights, 0u);
    inputs.geometry =
        std::make_shared<const SceneGeometry>(test::closed_box({glm::vec3(0.5f), glm::vec3(1.0f)}));
    const BakeFootprint footprint = estimate_bake_footprint(inputs, false);
    EXPECT_EQ(footprint.tree_lights, kMaxAreaLights);
    // Measured: 2,226-2,290 MiB at its peak, run to the end (2.5 GB the audit saw before the builder shrank).
    EXPECT_GT(footprint.bytes, 2290 * kMiB);
    EXPECT_LT(footprint.bytes, 2290 * kMiB * 5 / 4);
}

// Russian roulette ends a path after 1 / (1 - survival) lights on average,
// survival the brightest albedo (at most kVplMaxSurvival): twice that is reserved.
TEST(BakeFootprint, VplsAreBoundedByTheRoulettesPathLengthBouncesAndTheCap) {
    BakeInputs inputs = with_lights(4);
    inputs.geometry =
        std::make_shared<const SceneGeometry>(test::closed_box({glm::vec3(1.0f), glm::vec3(0.0f)}));
    inputs.indirect.method = IndirectMethod::kVpl;
    inputs.indirect.vpl.particle_count = 1000;
    inputs.indirect.vpl.bounces = 3;
    EXPECT_EQ(estimate_bake_footprint(inputs, false).max_vpls, 3000u);
    inputs.indirect.vpl.bounces = 65535;  // white walls: survival 0.95, 2 x 20 lights a path
    EXPECT_EQ(estimate_bake_footprint(inputs, false).max_vpls, 40000u);
    inputs.geometry = std::make_shared<const SceneGeometry>(test::closed_box(test::reflecting(0.5f, 0.0f)));
    EXPECT_EQ(estimate_bake_footprint(inputs, false).max_vpls, 4000u);  // 2 x 2 lights a path
    inputs.indirect.vpl.particle_count = 2000000;
    EXPECT_EQ(estimate_bake_footprint(inputs, false).max_vpls, kMaxIndirectLights);  // 8 million: capped
    inputs.indirect.vpl.particle_count = uint64_t{1} << 30;
    inputs.indirect.vpl.bounces = 1;
    const BakeFootprint huge = estimate_bake_footprint(inputs, false);
    EXPECT_EQ(huge.max_vpls, kMaxIndirectLights);
    EXPECT_EQ(huge.tree_lights, 4 + kMaxIndirectLights);
}

TEST(BakeFootprint, RadiosityCountsItsPatches) {
    BakeInputs inputs = with_lights(0);
    inputs.geometry =
        std::make_shared<const SceneGeometry>(test::closed_box({glm::vec3(0.5f), glm::vec3(0.0f)}));
    inputs.indirect.method = IndirectMethod::kRadiosity;
    inputs.indirect.radiosity.patch_size = 0.25f;  // edges 1 and 1.41: k = 6 on every triangle
    const BakeFootprint footprint = estimate_bake_footprint(inputs, false);
    EXPECT_EQ(footprint.tree_lights, 12u * 36u);
    EXPECT_EQ(footprint.bytes,
              kBakeFixedBytes + 12 * kRayCasterBytesPerTriangle +
                  12 * 36 * (kBytesPerPatch + kTreeBytesPerLight + kExactPairingBytesPerNode));
}

TEST(BakeFootprint, MegabytesReadWithThousandsSeparators) {
    EXPECT_EQ(megabytes_text(1), "1 MB");
    EXPECT_EQ(megabytes_text(3072 * kMiB), "3,072 MB");
    EXPECT_EQ(megabytes_text(1234567 * kMiB), "1,234,567 MB");
}

}  // namespace
}  // namespace lc::bake
