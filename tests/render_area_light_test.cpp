// An emissive square over a floor, rendered on the GPU (lavapipe) with the
// tree the bake pipeline makes from the client's geometry: the floor against
// the closed-form rectangle form factor (SPEC.md §11) in reference mode and in
// lightcuts at E = 0.005, and the panel showing exactly its emission (its own
// samples add nothing to it: the light it casts comes from the tree once).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>

#include "editor_client/render/renderer.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "editor_client/scene/surface_geometry.h"
#include "lightmass_server/mpi/bake_dispatch.h"
#include "rectangle_form_factor.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

constexpr float kRadiance = 5.0f, kSide = 1.0f, kHeight = 1.0f, kAlbedo = 0.5f;

Scene panel_over_floor() {
    Scene scene;
    Material floor;
    floor.base_color_factor = {kAlbedo, kAlbedo, kAlbedo, 1.0f};
    floor.metallic = 0.0f;
    Material panel = floor;
    panel.emissive_factor = glm::vec3(kRadiance);
    scene.materials = {floor, panel};
    scene.meshes.push_back(test::make_quad({-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, 0));
    const float h = kSide / 2;
    scene.meshes.push_back(test::make_quad({-h, kHeight, -h}, {kSide, 0, 0}, {0, 0, kSide}, 1));
    scene.bounds_min = {-5, 0, -5};
    scene.bounds_max = {5, kHeight, 5};
    return scene;
}

using AreaLightRender = test::VulkanTest;

TEST_F(AreaLightRender, FloorMatchesTheFormFactorAndThePanelShowsItsEmission) {
    const Scene scene = panel_over_floor();
    std::shared_ptr<const SceneGeometry> geometry = geometry_the_bake_needs(scene);
    ASSERT_NE(geometry, nullptr) << "the panel emits: the bake needs the geometry";
    bake::BakeInputs inputs;
    inputs.lights = std::make_shared<const std::vector<SceneLight>>();
    inputs.geometry = geometry;
    inputs.build.builder = BuilderKind::kAgglomerative;
    Result<bake::BuildResult> built = bake::run_bake(inputs, nullptr);
    ASSERT_TRUE(built.ok()) << built.error();
    const LightTree& tree = built->tree;
    ASSERT_EQ(tree.leaf_count, kDefaultAreaLights);

    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    RenderSettings settings;
    settings.width = settings.height = 48;
    settings.camera.eye = {0.0f, 0.6f, 2.2f};
    settings.camera.target = {0.0f, 0.3f, 0.0f};
    settings.camera.yfov = 1.3f;
    settings.criterion = CutCriterion::kBound;
    settings.error_ratio = 0.005f;
    // One lux from straight above: a point's response to it is its f_r.
    SceneLight unit_sun = test::directional_light({0, -1, 0}, glm::vec3(1.0f), 1.0f);
    for (RenderMode mode : {RenderMode::kReference, RenderMode::kLightcuts}) {
        SCOPED_TRACE(mode == RenderMode::kReference ? "reference" : "lightcuts");
        settings.mode = mode;
        const double tolerance = mode == RenderMode::kReference ? 0.01 : 0.02;
        Result<RenderStats> stats = (*renderer)->render(settings);
        ASSERT_TRUE(stats.ok()) << stats.error();
        Result<GBufferReadback> g = (*renderer)->read_gbuffer();
        Result<std::vector<float>> hdr = (*renderer)->read_hdr();
        ASSERT_TRUE(g.ok() && hdr.ok());
        size_t floor_pixels = 0, panel_pixels = 0;
        for (size_t i = 0; i < size_t(settings.width) * settings.height; ++i) {
            if (g->position[4 * i + 3] == 0.0f) continue;
            const glm::dvec3 x(g->position[4 * i], g->position[4 * i + 1], g->position[4 * i + 2]);
            const double radiance = (*hdr)[4 * i];
            if (g->normal[4 * i + 1] > 0.99f && std::abs(x.x) < 3.0 && std::abs(x.z) < 3.0) {
                // The floor's f_r (constant at roughness 1) times the closed-form E.
                const double f_r = shade_reference(std::span(&unit_sun, 1), test::gbuffer_point(*g, i)).x;
                const double expected = f_r * test::square_irradiance(kRadiance, kSide / 2.0, kHeight, x.x, x.z);
                EXPECT_NEAR(radiance, expected, tolerance * expected) << "floor at " << x.x << ", " << x.z;
                ++floor_pixels;
            } else if (g->normal[4 * i + 1] < -0.99f) {
                EXPECT_NEAR(radiance, kRadiance, 1e-4 * kRadiance) << "panel at " << x.x << ", " << x.z;
                ++panel_pixels;
            }
        }
        EXPECT_GT(floor_pixels, 300u);
        EXPECT_GT(panel_pixels, 20u);
    }
}

}  // namespace
}  // namespace lc::client
