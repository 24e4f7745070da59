// Instant radiosity's photon tracer: the furnace at a fixed seed, the
// bounce limit, determinism over thread counts, punctual and directional
// sources, cancellation.
#include "lightmass_server/indirect/vpl_tracer.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>

#include "indirect_scenes.h"

namespace lc::bake {
namespace {

glm::dvec3 total_power(const std::vector<IndirectLight>& lights) {
    glm::dvec3 sum(0.0);
    for (const IndirectLight& l : lights) sum += glm::dvec3(l.power);
    return sum;
}

Result<VplResult> trace(const SceneGeometry& g, std::span<const SceneLight> lights, const VplOptions& options,
                        const ProgressFn& progress = {}) {
    auto caster = RayCaster::build(g, 1);
    if (!caster.ok()) return caster.failure();
    return trace_vpls(g, *caster, lights, options, progress);
}

// Furnace: every wall emits E = pi L_e and reflects rho. The reflected power
// after B bounces is E A rho (1 - rho^B) / (1 - rho); the estimate at 20,000
// particles and this seed is within 2% (its standard error is about 0.5%).
TEST(VplTracer, FurnaceReflectsTheGeometricSeriesOfItsEmission) {
    const double rho = 0.5, radiance = 1.0, area = 6.0;
    SceneGeometry g = test::closed_box(test::reflecting(float(rho), float(radiance)));
    for (uint32_t bounces : {1u, 3u, 64u}) {
        VplOptions options;
        options.particle_count = 20000;
        options.bounces = bounces;
        options.seed = 7;
        auto r = trace(g, {}, options);
        ASSERT_TRUE(r.ok()) << r.error();
        double emitted = std::numbers::pi * radiance * area;
        EXPECT_NEAR(r->emitted_power.x / emitted, 1.0, 1e-5);
        double expected = emitted * rho * (1.0 - std::pow(rho, bounces)) / (1.0 - rho);
        glm::dvec3 power = total_power(r->lights);
        EXPECT_NEAR(power.x / expected, 1.0, 0.02) << bounces << " bounces";
        for (const IndirectLight& l : r->lights) {
            ASSERT_TRUE(std::isfinite(l.power.x) && l.power.x > 0.0f);
            ASSERT_NEAR(glm::length(l.normal), 1.0f, 1e-5f);
        }
        if (bounces == 1) {
            EXPECT_EQ(r->lights.size(), options.particle_count);
        }
    }
}

// The radiosity solver's hard cases for the photon tracer: a zero-area
// triangle, coincident floors and a touching panel in a furnace, at rho = 0.3
// and nearly white (0.99). The closed furnace keeps the geometric series of
// the emitted power; with the hard cases it is an upper bound (the panel is
// one-sided: photons reaching its back are absorbed, surface_sampling.h), so
// no duplicate surface may create power.
TEST(VplTracer, HardGeometryAndANearlyWhiteRoomStayFiniteAndBounded) {
    for (double rho : {0.3, 0.99}) for (bool hard : {false, true}) {
        SceneGeometry g = test::closed_box(test::reflecting(float(rho), 1.0f));
        if (hard) test::add_hard_cases(g);
        VplOptions options;
        options.particle_count = 20000;
        options.bounces = 16;
        options.seed = 7;
        auto r = trace(g, {}, options);
        ASSERT_TRUE(r.ok()) << r.error();
        const double expected = r->emitted_power.x * rho * (1.0 - std::pow(rho, 16.0)) / (1.0 - rho);
        for (const IndirectLight& l : r->lights) ASSERT_TRUE(std::isfinite(l.power.x) && l.power.x > 0.0f);
        const double ratio = total_power(r->lights).x / expected;
        std::printf("rho %.2f%s: reflected power / series %.4f\n", rho, hard ? ", hard cases" : "", ratio);
        if (hard) {
            EXPECT_LE(ratio, 1.03) << "rho " << rho;
        } else {
            EXPECT_NEAR(ratio, 1.0, 0.03) << "rho " << rho;
        }
    }
}

// 10^6 small triangles tiling the floor of the furnace (a millimetre above
// it, reflecting but not emitting): the tracer's BVH and its paths scale to
// them and stay finite. The floor's own light (a sixth of the emission) meets
// the tiles' backs and is absorbed; the rest reflects as in the furnace.
TEST(VplTracer, AMillionTrianglesStayFiniteAndBounded) {
    const double rho = 0.5;
    SceneGeometry g = test::closed_box(test::reflecting(float(rho), 1.0f));
    g.materials.push_back(test::reflecting(float(rho), 0.0f));
    const uint32_t tile_material = uint32_t(g.materials.size() - 1);
    const size_t walls = g.triangles.size();
    const int n = 708;  // 2 n^2 ~ 10^6
    const float step = 1.0f / n;
    for (int i = 0; i < n; ++i) {
        for (int k = 0; k < n; ++k) {
            test::add_quad(g, {i * step, 0.001f, k * step}, {0, 0, step}, {step, 0, 0}, tile_material);
        }
    }
    ASSERT_GE(g.triangles.size(), 1000000u);
    VplOptions options;
    options.particle_count = 20000;
    options.bounces = 8;
    options.seed = 7;
    auto r = trace(g, {}, options);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_FALSE(r->lights.empty());
    for (const IndirectLight& l : r->lights) ASSERT_TRUE(std::isfinite(l.power.x) && l.power.x > 0.0f);
    const double series = r->emitted_power.x * rho * (1.0 - std::pow(rho, 8.0)) / (1.0 - rho);
    const double ratio = total_power(r->lights).x / series;
    std::printf("10^6 triangles (%zu walls): %zu VPLs, reflected power / series %.4f\n", walls,
                r->lights.size(), ratio);
    EXPECT_NEAR(ratio, 5.0 / 6.0, 0.03);
}

TEST(VplTracer, SameLightsAtAnyThreadCount) {
    SceneGeometry g = test::cornell_box().geometry;
    VplOptions options;
    options.particle_count = 5000;
    options.bounces = 4;
    options.seed = 3;
    std::vector<IndirectLight> one, many;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        auto r = trace(g, {}, options);
        ASSERT_TRUE(r.ok());
        one = r->lights;
    }
    {
        tbb::global_control wide(tbb::global_control::max_allowed_parallelism, 4);
        auto r = trace(g, {}, options);
        ASSERT_TRUE(r.ok());
        many = r->lights;
    }
    ASSERT_EQ(one.size(), many.size());
    EXPECT_EQ(std::memcmp(one.data(), many.data(), one.size() * sizeof(IndirectLight)), 0);
    options.seed = 4;
    auto other = trace(g, {}, options);
    ASSERT_TRUE(other.ok());
    bool same = other->lights.size() == one.size() &&
                std::memcmp(other->lights.data(), one.data(), one.size() * sizeof(IndirectLight)) == 0;
    EXPECT_FALSE(same) << "another seed must draw other particles";
}

// A point light in a closed box of albedo rho: first-bounce deposits carry rho
// times its whole power 4 pi I; a directional light's disc power lands on the
// floor of an open box when it shines straight down.
TEST(VplTracer, PunctualAndDirectionalLightsShootTheirPower) {
    SceneGeometry box = test::closed_box(test::reflecting(0.5f, 0.0f));
    SceneLight point;
    point.type = LightType::kPoint;
    point.position = {0.5f, 0.5f, 0.5f};
    point.intensity = 2.0f;
    VplOptions options;
    options.particle_count = 4000;
    options.bounces = 1;
    auto r = trace(box, std::span<const SceneLight>(&point, 1), options);
    ASSERT_TRUE(r.ok());
    EXPECT_NEAR(total_power(r->lights).x, 0.5 * 4.0 * std::numbers::pi * 2.0, 1e-3);

    SceneGeometry floor;
    floor.materials.push_back(test::reflecting(0.5f, 0.0f));
    test::add_quad(floor, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0);
    SceneLight sun;
    sun.type = LightType::kDirectional;
    sun.direction = {0, -1, 0};
    sun.intensity = 3.0f;
    options.particle_count = 40000;
    auto lit = trace(floor, std::span<const SceneLight>(&sun, 1), options);
    ASSERT_TRUE(lit.ok());
    // E A rho, within the disc sampling's noise.
    EXPECT_NEAR(total_power(lit->lights).x / (3.0 * 1.0 * 0.5), 1.0, 0.03);
}

TEST(VplTracer, NothingToTraceGivesNoLightsAndCancellingStops) {
    SceneGeometry dark = test::closed_box({glm::vec3(0.5f), glm::vec3(0.0f)});
    auto none = trace(dark, {}, {});
    ASSERT_TRUE(none.ok());
    EXPECT_TRUE(none->lights.empty());

    SceneGeometry lit = test::closed_box({glm::vec3(0.5f), glm::vec3(1.0f)});
    VplOptions options;
    options.particle_count = 1000000;
    auto cancelled = trace(lit, {}, options, [](std::string_view stage, double) {
        EXPECT_EQ(stage, "indirect");
        return false;
    });
    ASSERT_FALSE(cancelled.ok());
    EXPECT_EQ(cancelled.error_kind(), ErrorKind::kCancelled);
}

}  // namespace
}  // namespace lc::bake
