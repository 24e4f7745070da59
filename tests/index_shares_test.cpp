// Index ranges of a sampler's work (lightmass_server/builders/index_range.h): the
// shares of area-light samples, environment strata and VPL paths, made apart
// and concatenated in order, are the whole run's bytes.
#include <gtest/gtest.h>

#include <cstring>

#include "lightmass_server/emitters/area_light_sampler.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/builders/index_range.h"
#include "lightmass_server/indirect/vpl_tracer.h"
#include "multi_rank_fixtures.h"
#include "protocol/channel_records.h"

namespace lc::bake {
namespace {

using test::cornell_inputs;

TEST(IndexShares, CoverTheRangeInOrderWithoutGaps) {
    for (uint32_t parts : {1u, 2u, 3u, 4u, 7u}) {
        uint64_t next = 0;
        for (uint32_t p = 0; p < parts; ++p) {
            const IndexRange share = share_of(10, p, parts);
            EXPECT_EQ(share.begin, next);
            EXPECT_LE(share.end - share.begin, 10 / parts + 1);
            next = share.end;
        }
        EXPECT_EQ(next, 10u);
    }
}

TEST(IndexShares, AreaSamplesOfTheSharesAreTheWholeRunsBytes) {
    const SceneGeometry geometry = test::cornell_box().geometry;
    Result<AreaLightSampling> whole = sample_area_lights(geometry, 301, 5);
    ASSERT_TRUE(whole.ok());
    for (uint32_t parts : {2u, 3u, 4u}) {
        std::vector<SceneLight> joined;
        for (uint32_t p = 0; p < parts; ++p) {
            Result<AreaLightSampling> part = sample_area_lights(geometry, 301, 5, share_of(301, p, parts));
            ASSERT_TRUE(part.ok());
            joined.insert(joined.end(), part->lights.begin(), part->lights.end());
        }
        EXPECT_EQ(encode_scene_channel(joined), encode_scene_channel(whole->lights)) << parts << " shares";
    }
}

// A map with a dark band: strata without power leave gaps in the slots.
Environment banded_map() {
    Environment environment;
    environment.map.width = 64;
    environment.map.height = 32;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 64; ++x)
            environment.map.texels.push_back(x >= 20 && x < 30 ? glm::vec3(0.0f)
                                                               : glm::vec3(0.1f * float(x % 7), 1.0f, 2.0f));
    return environment;
}

TEST(IndexShares, EnvironmentLightsOfTheSharesAreTheWholeRunsBytes) {
    Environment sky;
    sky.sky = SkyParameters{30.0f, 40.0f, 3.0f};
    for (const Environment& environment : {banded_map(), sky}) {
        Result<EnvironmentLights> whole = sample_environment(environment, 1001, 9);
        ASSERT_TRUE(whole.ok());
        ASSERT_GT(whole->lights.size(), 500u);
        for (uint32_t parts : {2u, 3u, 4u}) {
            std::vector<SceneLight> joined;
            for (uint32_t p = 0; p < parts; ++p) {
                Result<EnvironmentLights> part = sample_environment(environment, 1001, 9, p, parts);
                ASSERT_TRUE(part.ok());
                joined.insert(joined.end(), part->lights.begin(), part->lights.end());
            }
            EXPECT_EQ(encode_scene_channel(joined), encode_scene_channel(whole->lights))
                << parts << " shares";
        }
    }
}

TEST(IndexShares, VplPathsOfTheSharesAreTheWholeRunsBytes) {
    const BakeInputs inputs = cornell_inputs();
    Result<RayCaster> caster = RayCaster::build(*inputs.geometry, 1);
    ASSERT_TRUE(caster.ok());
    Result<AreaLightSampling> emitters = sample_area_lights(*inputs.geometry, 64, 1);
    ASSERT_TRUE(emitters.ok());
    Result<VplResult> whole =
        trace_vpls(*inputs.geometry, *caster, emitters->lights, inputs.indirect.vpl, {});
    ASSERT_TRUE(whole.ok());
    ASSERT_GT(whole->lights.size(), 1000u);
    for (uint32_t parts : {2u, 3u, 4u}) {
        std::vector<IndirectLight> joined;
        for (uint32_t p = 0; p < parts; ++p) {
            VplOptions share = inputs.indirect.vpl;
            share.particles = share_of(share.particle_count, p, parts);
            Result<VplResult> part = trace_vpls(*inputs.geometry, *caster, emitters->lights, share, {});
            ASSERT_TRUE(part.ok());
            joined.insert(joined.end(), part->lights.begin(), part->lights.end());
        }
        ASSERT_EQ(joined.size(), whole->lights.size()) << parts << " shares";
        EXPECT_EQ(0, std::memcmp(joined.data(), whole->lights.data(), joined.size() * sizeof(IndirectLight)));
    }
}

}  // namespace
}  // namespace lc::bake
