// Progressive-refinement radiosity: the furnace, a near-white room, the
// step budget, cancellation and the geometry that breaks naive solvers.
#include "lightmass_server/indirect/radiosity_solver.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "indirect_scenes.h"

namespace lc::bake {
namespace {

// A closed box whose every surface emits E = pi L_e with reflectance rho.
SceneGeometry furnace(float rho, float radiance) {
    return test::closed_box(test::reflecting(rho, radiance), 1.0f);
}

Result<RadiosityResult> solve(const SceneGeometry& g, const RadiosityOptions& options,
                              const ProgressFn& progress = {}) {
    auto caster = RayCaster::build(g, 1);
    if (!caster.ok()) return caster.failure();
    return solve_radiosity(g, *caster, {}, options, progress);
}

void expect_finite(const RadiosityResult& r) {
    for (const glm::vec3& b : r.radiosity) ASSERT_TRUE(std::isfinite(b.x + b.y + b.z));
    for (const IndirectLight& l : r.lights) ASSERT_TRUE(std::isfinite(l.power.x + l.power.y + l.power.z));
}

TEST(RadiositySolver, FurnaceConvergesToEmissionOverOneMinusRho) {
    const float rho = 0.5f, radiance = 1.0f;
    RadiosityOptions options;
    options.patch_size = 0.25f;
    options.tolerance = 1e-4;
    auto r = solve(furnace(rho, radiance), options);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_TRUE(r->converged) << r->message;
    double expected = std::numbers::pi * radiance / (1.0 - rho);
    for (const glm::vec3& b : r->radiosity) ASSERT_NEAR(b.y / expected, 1.0, 0.01);
    // The lights carry the reflected part only: rho E / (1 - rho) over the box's area.
    double power = 0.0;
    for (const IndirectLight& l : r->lights) power += l.power.y;
    EXPECT_NEAR(power / (6.0 * expected * rho), 1.0, 0.01);
}

TEST(RadiositySolver, ReportsEnergyShotAsItConvergesAndCanBeCancelled) {
    RadiosityOptions options;
    options.patch_size = 0.5f;
    std::vector<double> percents;
    auto r = solve(furnace(0.5f, 1.0f), options, [&](std::string_view stage, double percent) {
        EXPECT_EQ(stage, "radiosity");
        percents.push_back(percent);
        return true;
    });
    ASSERT_TRUE(r.ok());
    ASSERT_GE(percents.size(), 2u);
    for (size_t i = 1; i < percents.size(); ++i) EXPECT_GE(percents[i], percents[i - 1]);
    EXPECT_GE(percents.back(), 99.0);
    EXPECT_GE(r->convergence.size(), 2u);

    int calls = 0;
    auto cancelled = solve(furnace(0.5f, 1.0f), options, [&](std::string_view, double) { return ++calls < 3; });
    ASSERT_FALSE(cancelled.ok());
    EXPECT_EQ(cancelled.error_kind(), ErrorKind::kCancelled);
}

TEST(RadiositySolver, ANearlyWhiteRoomConvergesWithinItsBudgetOrSaysWhy) {
    RadiosityOptions options;
    options.patch_size = 2.0f;  // one patch per triangle: 12
    options.tolerance = 0.01;
    auto r = solve(furnace(0.99f, 1.0f), options);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_TRUE(r->converged) << r->message;
    expect_finite(*r);
    // Reflected radiosity of the 99% furnace: 99 E, less the tolerance's share.
    double expected = std::numbers::pi * 0.99 / 0.01;
    double power = 0.0;
    for (const IndirectLight& l : r->lights) power += l.power.x;
    EXPECT_NEAR(power / (6.0 * expected), 1.0, 0.02);

    options.max_steps = 50;
    auto stopped = solve(furnace(0.99f, 1.0f), options);
    ASSERT_TRUE(stopped.ok());
    EXPECT_FALSE(stopped->converged);
    EXPECT_EQ(stopped->steps, 50u);
    EXPECT_GT(stopped->unshot_fraction, options.tolerance);
    EXPECT_NE(stopped->message.find("50 steps"), std::string::npos) << stopped->message;
    expect_finite(*stopped);
}

// Stopped with 30% of the power unshot, the ambient term (Cohen et al. 1988)
// puts it back: in a closed furnace of one reflectance it is exact.
TEST(RadiositySolver, TheAmbientTermStandsForThePowerLeftUnshot) {
    const float rho = 0.5f, radiance = 1.0f;
    RadiosityOptions options;
    options.patch_size = 0.25f;
    options.tolerance = 0.3;
    auto r = solve(furnace(rho, radiance), options);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_GT(r->unshot_fraction, 0.1);
    EXPECT_GT(r->ambient.y, 0.0);
    const double expected = std::numbers::pi * radiance / (1.0 - rho);
    double sum = 0.0, area = 0.0;
    for (size_t j = 0; j < r->radiosity.size(); ++j) {
        sum += double(r->radiosity[j].y) * double(r->mesh.patches[j].area);
        area += double(r->mesh.patches[j].area);
    }
    EXPECT_NEAR(sum / area / expected, 1.0, 0.01);
}

TEST(RadiositySolver, ZeroAreaCoincidentAndTouchingGeometryStaysFiniteAndBounded) {
    const float rho = 0.3f;
    SceneGeometry g = furnace(rho, 1.0f);
    test::add_hard_cases(g);
    RadiosityOptions options;
    options.patch_size = 0.25f;
    options.tolerance = 1e-3;
    auto r = solve(g, options);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_TRUE(r->converged) << r->message;
    EXPECT_EQ(r->mesh.skipped_degenerate, 1u);
    expect_finite(*r);
    // Coincident copies at most double what a point sees of the enclosure,
    // so B <= E / (1 - 2 rho); without them the furnace gives E / (1 - rho).
    double bound = std::numbers::pi / (1.0 - 2.0 * rho);
    double furnace_value = std::numbers::pi / (1.0 - rho);
    double highest = 0.0;
    for (const glm::vec3& b : r->radiosity) highest = std::max(highest, double(b.x));
    EXPECT_LE(highest, bound);
    EXPECT_GT(highest, furnace_value);
}

TEST(RadiositySolver, AMillionTrianglesRunWithinAStepBudget) {
    // 10^6 small triangles tiling the floor of a lit box.
    SceneGeometry g = furnace(0.5f, 0.0f);
    g.materials.push_back({glm::vec3(0.5f), glm::vec3(1.0f)});
    g.triangles[2].material = g.triangles[3].material = 1;  // the ceiling emits
    const int n = 708;  // 2 n^2 ~ 10^6
    float step = 1.0f / n;
    for (int i = 0; i < n; ++i) {
        for (int k = 0; k < n; ++k) {
            test::add_quad(g, {i * step, 0.001f, k * step}, {0, 0, step}, {step, 0, 0}, 0);
        }
    }
    ASSERT_GE(g.triangles.size(), 1000000u);
    RadiosityOptions options;
    options.patch_size = 1.0f;
    options.max_steps = 1;
    options.visibility_samples = 1;
    auto start = std::chrono::steady_clock::now();
    auto r = solve(g, options);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_FALSE(r->converged);
    EXPECT_FALSE(r->message.empty());
    expect_finite(*r);
    EXPECT_FALSE(r->lights.empty());
    std::printf("10^6 triangles: %zu patches, %llu steps in %.2f s\n", r->mesh.patches.size(),
                static_cast<unsigned long long>(r->steps),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace
}  // namespace lc::bake
