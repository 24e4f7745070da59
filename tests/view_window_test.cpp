// The view command: a real GLFW window and swapchain under xvfb-run (as a
// subprocess), and the frame loop driven by a headless window's input script.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "editor_client/render/image_io.h"
#include "editor_client/scene/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "editor_client/window/headless_window.h"
#include "editor_client/window/orbit_camera.h"
#include "editor_client/window/view_loop.h"
#include "lightmass_server/tree_builder.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/dump.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

Scene lit_room() {
    Scene scene = make_room_scene();
    LightLayoutOptions layout;
    layout.count = 12;
    layout.seed = 11;
    layout.box_min = kRoomLightBoxMin;
    layout.box_max = kRoomLightBoxMax;
    layout.range = 5.0f;
    Result<std::vector<SceneLight>> lights = generate_lights(layout);
    EXPECT_TRUE(lights.ok());
    if (lights.ok()) scene.lights = *lights;
    return scene;
}

TEST(OrbitCamera, StartsWhereTheCameraIsAndOrbitsAroundTheTarget) {
    RenderCamera start;
    start.eye = {3.0f, 2.0f, 4.0f};
    start.target = {0.5f, 1.0f, -1.0f};
    OrbitCamera orbit(start);
    RenderCamera same = orbit.camera();
    EXPECT_NEAR(glm::length(same.eye - start.eye), 0.0f, 1e-4f);
    float distance = glm::length(start.eye - start.target);
    orbit.orbit({200.0f, -50.0f});
    RenderCamera turned = orbit.camera();
    EXPECT_GT(glm::length(turned.eye - start.eye), 0.5f);
    EXPECT_NEAR(glm::length(turned.eye - turned.target), distance, 1e-4f);
    orbit.dolly(3.0f);
    EXPECT_NEAR(glm::length(orbit.camera().eye - orbit.camera().target), distance * 0.729f, 1e-3f);
    // Pitch stops short of the pole: the view never flips.
    orbit.orbit({0.0f, 1e6f});
    RenderCamera top = orbit.camera();
    EXPECT_LT((top.eye - top.target).y / glm::length(top.eye - top.target), 1.0f);
}

TEST(OrbitCamera, FliesAlongTheViewAndLooksAroundTheEye) {
    RenderCamera start;
    start.eye = {0.0f, 1.5f, 5.0f};
    start.target = {0.0f, 1.5f, 0.0f};
    OrbitCamera camera(start);
    // W for 2 units: eye and target move forward (-Z) together.
    camera.fly({0.0f, 0.0f, 1.0f}, 2.0f);
    RenderCamera moved = camera.camera();
    EXPECT_NEAR(moved.eye.z, 3.0f, 1e-4f);
    EXPECT_NEAR(moved.target.z, -2.0f, 1e-4f);
    EXPECT_NEAR(moved.eye.y, 1.5f, 1e-4f);
    // D + R: right (+X) and up, 1 unit along their diagonal.
    camera.fly({1.0f, 1.0f, 0.0f}, 1.0f);
    EXPECT_NEAR(camera.camera().eye.x, std::sqrt(0.5f), 1e-4f);
    EXPECT_NEAR(camera.camera().eye.y, 1.5f + std::sqrt(0.5f), 1e-4f);
    camera.fly({0.0f, 0.0f, 0.0f}, 1.0f);  // no keys: no move
    EXPECT_NEAR(camera.camera().eye.x, std::sqrt(0.5f), 1e-4f);
    // Looking around keeps the eye where it is and turns the view.
    const glm::vec3 eye = camera.camera().eye;
    const glm::vec3 forward = glm::normalize(camera.camera().target - eye);
    camera.look({150.0f, 40.0f});
    EXPECT_NEAR(glm::length(camera.camera().eye - eye), 0.0f, 1e-3f);
    EXPECT_LT(glm::dot(glm::normalize(camera.camera().target - camera.camera().eye), forward), 0.9f);
    EXPECT_GE(camera.fly_speed(), 0.5f);
}

TEST(ViewLoop, HeadlessScriptSwitchesModesAndOrbits) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    Scene scene = lit_room();
    Result<bake::BuildResult> built = bake::build_light_tree(scene.lights, {}, nullptr);
    ASSERT_TRUE(built.ok()) << built.error();
    Result<std::unique_ptr<Renderer>> renderer = Renderer::create(*context, scene, &built->tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();

    HeadlessWindow window(64, 48);
    WindowInput nothing;
    WindowInput cuts_and_drag;
    cuts_and_drag.mode_key = 3;
    cuts_and_drag.orbit_drag = {120.0f, 10.0f};
    WindowInput cutsize;
    cutsize.mode_key = 4;
    window.queue_input(nothing);
    window.queue_input(cuts_and_drag);
    window.queue_input(cutsize);

    ViewOptions options;
    options.settings.width = 64;
    options.settings.height = 48;
    options.settings.camera = camera_from_scene(scene.cameras.at(0));
    options.frames = 3;
    std::filesystem::path dir = test::make_temp_dir("view-loop");
    options.screenshot = dir / "last.png";
    Result<ViewSummary> summary = run_view_loop(window, *context, **renderer, options);
    ASSERT_TRUE(summary.ok()) << summary.error();
    EXPECT_EQ(summary->frames, 3u);
    EXPECT_EQ(summary->last_settings.mode, RenderMode::kCutSize);
    EXPECT_GT(glm::length(summary->last_settings.camera.eye - options.settings.camera.eye), 0.1f);
    EXPECT_NE(window.title().find("cutsize"), std::string::npos) << window.title();

    // The screenshot is the cutsize frame: its bottom rows hold the scale bar.
    Result<Rgba8Image> shot = read_png(options.screenshot);
    ASSERT_TRUE(shot.ok()) << shot.error();
    ASSERT_EQ(shot->width, 64u);
    const uint8_t* bottom_right = &shot->rgba[4 * (size_t(47) * 64 + 63)];
    EXPECT_GT(bottom_right[0], 200);  // the red end of the ramp
    EXPECT_EQ(context->validation_message_count(), 0u);
    std::filesystem::remove_all(dir);
}

TEST(ViewLoop, ModesThatNeedATreeAreRefusedWithoutOne) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    Scene scene = lit_room();
    Result<std::unique_ptr<Renderer>> renderer = Renderer::create(*context, scene, nullptr);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    HeadlessWindow window(32, 32);
    WindowInput lightcuts;
    lightcuts.mode_key = 2;
    window.queue_input(lightcuts);
    ViewOptions options;
    options.settings.width = options.settings.height = 32;
    options.settings.camera = camera_from_scene(scene.cameras.at(0));
    options.frames = 2;
    Result<ViewSummary> summary = run_view_loop(window, *context, **renderer, options);
    ASSERT_TRUE(summary.ok()) << summary.error();
    EXPECT_EQ(summary->last_settings.mode, RenderMode::kReference);
    EXPECT_EQ(context->validation_message_count(), 0u);
}

TEST(ViewWindow, XvfbWindowRendersFramesAndSavesAScreenshot) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run is not installed";
    std::unique_ptr<vk::Context> probe;
    LC_REQUIRE_VULKAN(probe);
    probe.reset();

    std::filesystem::path dir = test::make_temp_dir("view-window");
    Scene scene = lit_room();
    std::filesystem::path scene_path = dir / "room.gltf";
    ASSERT_TRUE(write_scene_gltf(scene, scene_path).ok());
    Result<bake::BuildResult> built = bake::build_light_tree(scene.lights, {}, nullptr);
    ASSERT_TRUE(built.ok()) << built.error();
    std::filesystem::path tree_path = dir / "room.lcut";
    ASSERT_TRUE(write_dump(tree_path, ChannelDump{lightcuts_result_channel_name(),
                                                  encode_result_channel(built->tree)})
                    .ok());

    for (const char* mode : {"reference", "cuts"}) {
        SCOPED_TRACE(mode);
        std::filesystem::path shot = dir / (std::string(mode) + ".png");
        std::filesystem::path log = dir / "view.log";
        std::string command = "xvfb-run -a " + (test::bin_dir() / "editor_client").string() +
                              " view " + scene_path.string() + " --tree " + tree_path.string() +
                              " --mode " + mode + " --size 96x72 --frames 3 --validation" +
                              " --screenshot " + shot.string() + " > " + log.string() + " 2>&1";
        int status = std::system(command.c_str());
        std::ifstream in(log);
        std::stringstream text;
        text << in.rdbuf();
        ASSERT_EQ(status, 0) << text.str();
        EXPECT_NE(text.str().find("3 frames"), std::string::npos) << text.str();
        EXPECT_NE(text.str().find("0 validation messages"), std::string::npos) << text.str();

        Result<Rgba8Image> image = read_png(shot);
        ASSERT_TRUE(image.ok()) << image.error();
        EXPECT_EQ(image->width, 96u);
        EXPECT_EQ(image->height, 72u);
        std::set<uint32_t> colours;
        size_t lit = 0;
        for (size_t i = 0; i < image->rgba.size(); i += 4) {
            uint32_t c = image->rgba[i] | image->rgba[i + 1] << 8 | image->rgba[i + 2] << 16;
            colours.insert(c);
            lit += (image->rgba[i] + image->rgba[i + 1] + image->rgba[i + 2]) > 30 ? 1 : 0;
        }
        EXPECT_GT(lit, image->rgba.size() / 4 / 4) << "the screenshot is mostly black";
        EXPECT_GT(colours.size(), 4u) << "the screenshot is blank";
    }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lc::client
