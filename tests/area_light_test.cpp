// Area lights from emissive triangles (lightmass_server/emitters/
// area_light_sampler.h, through the bake pipeline): the samples' energy, their
// share of the budget, stratification and determinism; a floor under a square
// emitter against the closed-form rectangle form factor (SPEC.md §11) in
// reference mode and in lightcuts; degenerate and bad input.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <cmath>
#include <numbers>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightmass_server/mpi/bake_dispatch.h"
#include "lightmass_server/emitters/area_light_sampler.h"
#include "protocol/channel_records.h"
#include "rectangle_form_factor.h"
#include "tree_fixtures.h"

namespace lc::bake {
namespace {

constexpr double kPi = std::numbers::pi;

void add_quad(SceneGeometry& g, glm::vec3 corner, glm::vec3 edge_a, glm::vec3 edge_b,
              uint32_t material) {
    const glm::vec3 n = glm::normalize(glm::cross(edge_a, edge_b));
    SurfaceTriangle a, b;
    a.positions[0] = corner;
    a.positions[1] = corner + edge_a;
    a.positions[2] = corner + edge_a + edge_b;
    b.positions[0] = corner;
    b.positions[1] = corner + edge_a + edge_b;
    b.positions[2] = corner + edge_b;
    for (SurfaceTriangle* t : {&a, &b}) {
        t->normals[0] = t->normals[1] = t->normals[2] = n;
        t->material = material;
        g.triangles.push_back(*t);
    }
}

// A floor at y = 0 and a `side` x `side` square emitter of radiance L centred
// `height` above the origin, facing down.
SceneGeometry floor_under_square(float side, float height, glm::vec3 radiance) {
    SceneGeometry g;
    SurfaceMaterial floor;
    SurfaceMaterial panel;
    panel.emission = radiance;
    g.materials = {floor, panel};
    add_quad(g, {-10, 0, -10}, {0, 0, 20}, {20, 0, 0}, 0);
    const float h = side / 2;
    add_quad(g, {-h, height, -h}, {h * 2, 0, 0}, {0, 0, h * 2}, 1);
    return g;
}

SurfacePoint floor_point(double x, double z) {
    SurfacePoint p;
    p.position = {x, 0, z};
    p.normal = {0, 1, 0};
    p.albedo = glm::dvec3(1.0);
    return p;
}

BakeInputs inputs_for(const SceneGeometry& g, uint32_t budget) {
    BakeInputs inputs;
    inputs.lights = std::make_shared<const std::vector<SceneLight>>();
    inputs.geometry = std::make_shared<const SceneGeometry>(g);
    inputs.area_lights = budget;
    inputs.build.builder = BuilderKind::kAgglomerative;
    inputs.build.seed = 5;
    return inputs;
}

TEST(AreaLights, SampleIntensitiesSumToTheEmittedPower) {
    SceneGeometry g = floor_under_square(1.0f, 1.0f, {17.0f, 12.0f, 4.0f});
    add_quad(g, {3, 2, 3}, {0.5f, 0, 0}, {0, 0, 2.0f}, 1);  // a second, larger panel
    Result<AreaLightSampling> s = sample_area_lights(g, 1000, 1);
    ASSERT_TRUE(s.ok()) << s.error();
    EXPECT_EQ(s->emissive_triangles, 4u);
    EXPECT_EQ(s->lights.size(), 1000u);
    glm::dvec3 expected(0.0), sum(0.0);
    for (const SurfaceTriangle& t : g.triangles) expected += emitted_power(g, t);
    EXPECT_NEAR(expected.x, kPi * 17.0 * 2.0, 1e-9);  // pi L A over both panels (1 + 1 m^2)
    for (const SceneLight& l : s->lights) {
        EXPECT_EQ(l.type, LightType::kOriented);
        EXPECT_EQ(l.direction, glm::vec3(0, -1, 0));
        sum += kPi * glm::dvec3(l.color) * double(l.intensity);  // a cosine emitter's power
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], expected[c], 1e-6 * expected[c]);
    // Equal power, equal shares: 250 samples per triangle of either panel.
    size_t on_small = 0;
    for (const SceneLight& l : s->lights) on_small += l.position.x < 2.0f ? 1 : 0;
    EXPECT_EQ(on_small, 500u);
}

TEST(AreaLights, SharesFollowPowerAndSamplesStayOnTheirTriangle) {
    SceneGeometry g = floor_under_square(1.0f, 1.0f, {1.0f, 1.0f, 1.0f});
    SurfaceMaterial bright;
    bright.emission = {3.0f, 3.0f, 3.0f};
    g.materials.push_back(bright);
    add_quad(g, {3, 2, 3}, {1, 0, 0}, {0, 0, 1}, 2);
    Result<AreaLightSampling> s = sample_area_lights(g, 800, 9);
    ASSERT_TRUE(s.ok()) << s.error();
    size_t dim = 0;
    for (const SceneLight& l : s->lights) {
        const bool on_dim = std::abs(l.position.x) <= 0.5f && std::abs(l.position.z) <= 0.5f &&
                            l.position.y == 1.0f;
        const bool on_bright = l.position.x >= 3.0f && l.position.x <= 4.0f && l.position.z >= 3.0f &&
                               l.position.z <= 4.0f && l.position.y == 2.0f;
        EXPECT_TRUE(on_dim || on_bright) << l.position.x << " " << l.position.y << " " << l.position.z;
        dim += on_dim ? 1 : 0;
    }
    EXPECT_EQ(dim, 200u);  // a quarter of the power, a quarter of the samples
    // Stratified: every cell of a 5 x 5 grid over the dim panel holds a sample.
    std::vector<int> cells(25, 0);
    for (const SceneLight& l : s->lights) {
        if (l.position.y != 1.0f) continue;
        const int i = std::min(4, int((l.position.x + 0.5f) * 5));
        const int j = std::min(4, int((l.position.z + 0.5f) * 5));
        ++cells[size_t(i * 5 + j)];
    }
    for (int count : cells) EXPECT_GT(count, 0);
}

TEST(AreaLights, DeterministicForASeedAndBudgetRules) {
    const SceneGeometry g = floor_under_square(1.0f, 1.0f, {2.0f, 2.0f, 2.0f});
    Result<AreaLightSampling> a = sample_area_lights(g, 64, 3), b = sample_area_lights(g, 64, 3),
                              c = sample_area_lights(g, 64, 4);
    ASSERT_TRUE(a.ok() && b.ok() && c.ok());
    ASSERT_EQ(a->lights.size(), b->lights.size());
    bool differs = false;
    for (size_t i = 0; i < a->lights.size(); ++i) {
        EXPECT_EQ(a->lights[i].position, b->lights[i].position);
        EXPECT_EQ(a->lights[i].guid, b->lights[i].guid);
        differs = differs || a->lights[i].position != c->lights[i].position;
    }
    EXPECT_TRUE(differs) << "the seed changes the strata's jitter";
    // A budget below the triangle count: one sample each, said so.
    Result<AreaLightSampling> one = sample_area_lights(g, 1, 3);
    ASSERT_TRUE(one.ok());
    EXPECT_TRUE(one->budget_raised);
    EXPECT_EQ(one->lights.size(), 2u);
    Result<AreaLightSampling> zero = sample_area_lights(g, 0, 3);
    ASSERT_FALSE(zero.ok());
    EXPECT_NE(zero.error().find("budget is 0"), std::string::npos) << zero.error();
}

// The paper's area lights against the closed form: within 1% summing every
// sample (reference) at the default budget, within 2% through the tree's
// cuts at error ratio 0.005.
TEST(AreaLights, FloorUnderASquareEmitterMatchesTheFormFactor) {
    const double L = 5.0, side = 1.0, height = 1.0;
    const SceneGeometry g = floor_under_square(float(side), float(height), glm::vec3(float(L)));
    Result<BuildResult> built = run_bake(inputs_for(g, kDefaultAreaLights), nullptr);
    ASSERT_TRUE(built.ok()) << built.error();
    EXPECT_EQ(built->tree.leaf_count, kDefaultAreaLights);
    const WalkTree tree = test::walk_tree(built->tree);
    CutSettings cuts;
    cuts.criterion = CutCriterion::kBound;
    cuts.error_ratio = 0.005;
    for (const glm::dvec2 xz : {glm::dvec2(0, 0), glm::dvec2(0.3, 0.1), glm::dvec2(0.5, 0.5),
                                glm::dvec2(1.0, -0.4), glm::dvec2(2.0, 1.5)}) {
        const double expected = test::square_irradiance(L, side / 2, height, xz.x, xz.y);
        const SurfacePoint p = floor_point(xz.x, xz.y);
        // Albedo 1: L_out = E / pi.
        const double reference = kPi * shade_tree_leaves(tree, p).x;
        const double lightcuts = kPi * shade_lightcuts(tree, {}, p, cuts).radiance.x;
        EXPECT_NEAR(reference, expected, 0.01 * expected) << xz.x << ", " << xz.y;
        EXPECT_NEAR(lightcuts, expected, 0.02 * expected) << xz.x << ", " << xz.y;
    }
}

TEST(AreaLights, TreesAreByteIdenticalAtAnyThreadCount) {
    const SceneGeometry g = floor_under_square(1.0f, 1.0f, {1.0f, 0.5f, 0.25f});
    BakeInputs inputs = inputs_for(g, 2000);
    inputs.raycast_threads = 1;
    Result<BuildResult> one = run_bake(inputs, nullptr);
    inputs.raycast_threads = 2;
    Result<BuildResult> two = run_bake(inputs, nullptr);
    ASSERT_TRUE(one.ok() && two.ok());
    EXPECT_EQ(encode_result_channel(one->tree), encode_result_channel(two->tree));
    ASSERT_EQ(one->report.effects.size(), 2u);
    EXPECT_EQ(one->report.effects[0], "area lights: simulated (2 emissive triangles, 2000 samples)");
    EXPECT_EQ(one->report.effects[1], "indirect: skipped: no bounce requested");
}

TEST(AreaLights, SamplesFollowTheLightsGivenBeforeThemAndTheBakeTreeIsTheSame) {
    const SceneGeometry g = floor_under_square(1.0f, 1.0f, {1.0f, 0.5f, 0.25f});
    std::vector<SceneLight> scene(3);
    for (uint32_t i = 0; i < scene.size(); ++i) {
        scene[i].guid = Guid{7, i, 0, 1};
        scene[i].position = {float(i), 2.0f, 0.5f};
    }
    BakeInputs inputs = inputs_for(g, 500);
    Result<AreaLightSampling> alone = sample_area_lights(g, 500, inputs.build.seed);
    Result<AreaLightSampling> after =
        sample_area_lights(g, 500, inputs.build.seed, IndexRange{}, nullptr, scene);
    ASSERT_TRUE(alone.ok() && after.ok());
    ASSERT_EQ(after->lights.size(), scene.size() + alone->lights.size());
    for (size_t i = 0; i < after->lights.size(); ++i) {
        const SceneLight& want = i < scene.size() ? scene[i] : alone->lights[i - scene.size()];
        EXPECT_EQ(after->lights[i].guid, want.guid) << i;
        EXPECT_EQ(after->lights[i].position, want.position) << i;
    }
    // The bake samples after a copy of the scene's lights: its tree is the one of the lights joined by hand.
    inputs.lights = std::make_shared<const std::vector<SceneLight>>(scene);
    Result<BuildResult> baked = run_bake(inputs, nullptr);
    Result<BuildResult> by_hand = build_light_tree(after->lights, inputs.build, nullptr);
    ASSERT_TRUE(baked.ok() && by_hand.ok());
    EXPECT_EQ(baked->tree.leaf_count, 503u);
    EXPECT_EQ(encode_result_channel(baked->tree), encode_result_channel(by_hand->tree));
    EXPECT_EQ(baked->report.effects[0], "area lights: simulated (2 emissive triangles, 500 samples)");
    // No triangle emits: the lights given before are dropped with the (empty) samples.
    const SceneGeometry dark = floor_under_square(1.0f, 1.0f, glm::vec3(0.0f));
    Result<AreaLightSampling> none = sample_area_lights(dark, 500, 1, IndexRange{}, nullptr, scene);
    ASSERT_TRUE(none.ok());
    EXPECT_TRUE(none->lights.empty());
}

TEST(AreaLights, WithoutEmissionOrGeometryTheCensusSaysSkipped) {
    SceneGeometry dark = floor_under_square(1.0f, 1.0f, glm::vec3(0.0f));
    // Degenerate emitters only: nothing to sample, no failure.
    dark.materials[1].emission = {1, 1, 1};
    for (SurfaceTriangle& t : dark.triangles)
        if (t.material == 1) t.positions[2] = t.positions[1];
    BakeInputs inputs = inputs_for(dark, 100);
    auto point = std::make_shared<std::vector<SceneLight>>(1);
    (*point)[0].guid = Guid{1, 2, 3, 4};
    (*point)[0].position = {0, 2, 0};
    inputs.lights = point;
    for (bool with_geometry : {true, false}) {
        if (!with_geometry) inputs.geometry = nullptr;
        Result<BuildResult> built = run_bake(inputs, nullptr);
        ASSERT_TRUE(built.ok()) << built.error();
        EXPECT_EQ(built->tree.leaf_count, 1u);
        ASSERT_EQ(built->report.effects.size(), 2u);
        EXPECT_EQ(built->report.effects[0], "area lights: skipped: no drawn triangle emits power");
        EXPECT_EQ(built->report.effects[1], "indirect: skipped: no bounce requested");
    }
}

}  // namespace
}  // namespace lc::bake
