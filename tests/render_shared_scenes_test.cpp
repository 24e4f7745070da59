// The shared glTF scenes render in every mode: finite output, not black in
// reference mode, zero validation messages. cornell_box has no lights of its
// own, so the test hangs a grid of point lights under its ceiling.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "editor_client/render/renderer.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "lightmass_server/builders/tree_builder.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

constexpr uint32_t kSize = 96;

void add_ceiling_lights(Scene& scene) {
    const glm::vec3 lo = scene.bounds_min, hi = scene.bounds_max;
    const glm::vec3 extent = hi - lo;
    uint32_t index = 0;
    for (int i = 0; i < 4; ++i) {
        for (int k = 0; k < 4; ++k) {
            glm::vec3 p(lo.x + extent.x * (0.2f + 0.2f * float(i)), lo.y + extent.y * 0.9f,
                        lo.z + extent.z * (0.2f + 0.2f * float(k)));
            SceneLight light =
                test::point_light(p, {1.0f, 0.95f, 0.85f}, 2e3f, 0.8f * glm::length(extent));
            test::set_unit_guid(light, index++);
            scene.lights.push_back(light);
        }
    }
}

// cornell_box is open towards -Z and has no camera: look in through the opening
// (the classic Cornell box view).
RenderCamera cornell_camera() {
    RenderCamera camera;
    camera.eye = {278.0f, 273.0f, -800.0f};
    camera.target = {278.0f, 273.0f, 0.0f};
    camera.yfov = 39.0f * 3.14159265f / 180.0f;
    return camera;
}

void render_every_mode(const std::filesystem::path& path, bool add_lights,
                       std::optional<RenderCamera> camera) {
    std::unique_ptr<vk::Context> context;
    std::string why;
    context = test::make_headless_context(why);
    if (!context) GTEST_SKIP() << "no Vulkan device: " << why;

    Result<Scene> scene = load_scene(path);
    ASSERT_TRUE(scene.ok()) << scene.error();
    if (add_lights) add_ceiling_lights(*scene);
    ASSERT_FALSE(scene->lights.empty());
    Result<bake::BuildResult> built = bake::build_light_tree(scene->lights, {}, nullptr);
    ASSERT_TRUE(built.ok()) << built.error();

    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context, *scene, &built->tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    RenderSettings settings;
    settings.width = settings.height = kSize;
    settings.camera = camera ? *camera : frame_scene_bounds(*scene, 1.0f);
    for (RenderMode mode : {RenderMode::kReference, RenderMode::kLightcuts, RenderMode::kCuts,
                            RenderMode::kCutSize}) {
        SCOPED_TRACE(render_mode_name(mode));
        settings.mode = mode;
        Result<RenderStats> stats = (*renderer)->render(settings);
        ASSERT_TRUE(stats.ok()) << stats.error();
        EXPECT_EQ(stats->nonfinite_pixels, 0u);
        EXPECT_GT(stats->geometry_pixels, kSize * kSize / 20);
        Result<std::vector<float>> hdr = (*renderer)->read_hdr();
        Result<std::vector<uint8_t>> display = (*renderer)->read_display();
        ASSERT_TRUE(hdr.ok() && display.ok());
        double sum = 0.0;
        for (float v : *hdr) {
            ASSERT_TRUE(std::isfinite(v));
            sum += v;
        }
        size_t lit = 0;
        for (size_t i = 0; i < display->size(); i += 4)
            if ((*display)[i] + (*display)[i + 1] + (*display)[i + 2] > 30) ++lit;
        if (mode == RenderMode::kReference) {
            EXPECT_GT(sum, 0.0);
            EXPECT_GT(lit, stats->geometry_pixels / 10) << "reference render is (nearly) black";
        }
        if (mode != RenderMode::kReference) {
            EXPECT_GT(lit, 0u);
            EXPECT_GE(stats->cuts.max_cut, 1u);
        }
    }
    EXPECT_EQ(context->validation_message_count(), 0u);
}

TEST(RenderSharedScenes, LightsPunctualLamp) {
    LC_REQUIRE_SHARED_SCENES();
    render_every_mode(test::shared_scenes_dir() / "LightsPunctualLamp" / "LightsPunctualLamp.gltf",
                      false, std::nullopt);
}

TEST(RenderSharedScenes, CornellBoxWithCeilingLights) {
    LC_REQUIRE_SHARED_SCENES();
    render_every_mode(test::shared_scenes_dir() / "cornell_box" / "cornell_box.gltf", true,
                      cornell_camera());
}

}  // namespace
}  // namespace lc::client
