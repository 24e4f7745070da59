// The view command: a real GLFW window and swapchain under xvfb-run (as a
// subprocess), and the editor's frame loop driven by a headless window's input.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "editor_client/bake/server_process.h"
#include "editor_client/editor/editor_session.h"
#include "editor_client/render/output/image_io.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "editor_client/window/editor_loop.h"
#include "editor_client/window/headless_window.h"
#include "editor_client/window/orbit_camera.h"
#include "lightcuts/version.h"
#include "protocol/asio.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

// The scene's tree as the server builds it, written as `bake -o` writes it.
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

TEST(EditorLoop, HeadlessInputSwitchesModesAndOrbits) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    std::filesystem::path dir = test::make_temp_dir("view-loop");
    Scene scene = test::lit_room(11);
    const RenderCamera camera = camera_from_scene(scene.cameras.at(0));
    const std::filesystem::path tree = test::write_tree_dump(scene, dir);
    EditorSession session(std::move(scene));
    ASSERT_TRUE(session.view_settings().set_camera(camera));
    Status imported = session.import_tree_dump(tree);
    ASSERT_TRUE(imported.ok()) << imported.error();

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

    EditorLoopOptions options;
    options.width = 64;
    options.height = 48;
    options.frames = 3;
    options.adaptive_resolution = false;  // every frame at full size, as the title says
    options.screenshot = dir / "last.png";
    Result<EditorLoopSummary> summary = run_editor_loop(window, *context, session, options);
    ASSERT_TRUE(summary.ok()) << summary.error();
    EXPECT_EQ(summary->frames, 3u);
    EXPECT_EQ(summary->last_mode, RenderMode::kCutSize);
    EXPECT_GT(glm::length(session.view().camera.eye - camera.eye), 0.1f);
    EXPECT_NE(window.title().find("64x48"), std::string::npos) << window.title();

    // The screenshot is the cutsize frame: its bottom rows hold the scale bar.
    Result<Rgba8Image> shot = read_png(options.screenshot);
    ASSERT_TRUE(shot.ok()) << shot.error();
    ASSERT_EQ(shot->width, 64u);
    const uint8_t* bottom_right = &shot->rgba[4 * (size_t(47) * 64 + 63)];
    EXPECT_GT(bottom_right[0], 200);  // the red end of the ramp
    EXPECT_EQ(context->validation_message_count(), 0u);
    std::filesystem::remove_all(dir);
}

TEST(EditorLoop, ModesThatNeedATreeRenderTheReferenceWithoutOne) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    Scene scene = test::lit_room(11);
    const RenderCamera camera = camera_from_scene(scene.cameras.at(0));
    EditorSession session(std::move(scene));
    ASSERT_TRUE(session.view_settings().set_camera(camera));
    HeadlessWindow window(32, 32);
    WindowInput lightcuts;
    lightcuts.mode_key = 2;
    window.queue_input(lightcuts);
    EditorLoopOptions options;
    options.width = options.height = 32;
    options.frames = 2;
    Result<EditorLoopSummary> summary = run_editor_loop(window, *context, session, options);
    ASSERT_TRUE(summary.ok()) << summary.error();
    // The choice is kept for when a tree arrives; until then the view is exact.
    EXPECT_EQ(session.view().mode, RenderMode::kLightcuts);
    EXPECT_EQ(summary->last_mode, RenderMode::kReference);
    EXPECT_EQ(context->validation_message_count(), 0u);
}

// Runs `command` with its output into `log`; its exit status and the log's text.
std::pair<int, std::string> run_logged(const std::string& command, const std::filesystem::path& log) {
    const int status = std::system((command + " > " + log.string() + " 2>&1").c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    return {status, text.str()};
}

// The view command in a real window: skipped without xvfb-run or a Vulkan device.
class ViewWindow : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
            GTEST_SKIP() << "xvfb-run is not installed";
        std::unique_ptr<vk::Context> probe;
        LC_REQUIRE_VULKAN(probe);
    }
};

TEST_F(ViewWindow, XvfbWindowRendersFramesAndSavesAScreenshot) {

    std::filesystem::path dir = test::make_temp_dir("view-window");
    Scene scene = test::lit_room(11);
    std::filesystem::path scene_path = dir / "room.gltf";
    ASSERT_TRUE(write_scene_gltf(scene, scene_path).ok());
    const std::filesystem::path tree_path = test::write_tree_dump(scene, dir);

    for (const char* mode : {"reference", "cuts"}) {
        SCOPED_TRACE(mode);
        std::filesystem::path shot = dir / (std::string(mode) + ".png");
        std::filesystem::path log = dir / "view.log";
        std::string command = "xvfb-run -a " + (test::bin_dir() / "editor_client").string() +
                              " view " + scene_path.string() + " --tree " + tree_path.string() +
                              " --mode " + mode + " --size 96x72 --frames 3 --validation" +
                              " --screenshot " + shot.string();
        const auto [status, text] = run_logged(command, log);
        ASSERT_EQ(status, 0) << text;
        EXPECT_NE(text.find("3 frames"), std::string::npos) << text;
        EXPECT_NE(text.find("0 validation messages"), std::string::npos) << text;

        Result<Rgba8Image> image = read_png(shot);
        ASSERT_TRUE(image.ok()) << image.error();
        EXPECT_EQ(image->width, 96u);
        EXPECT_EQ(image->height, 72u);
        test::expect_not_blank(*image, "the screenshot", 4);
    }
    std::filesystem::remove_all(dir);
}

// Build Lighting from a real window (issue 16): a scripted bake of the
// emissive Cornell box with radiosity indirect light on a spawned server.
// The tree holds the panel's 256 area-light samples and the patches
// (EditorBake tests the solver's stage in the progress bar).
TEST_F(ViewWindow, XvfbBuildLightingBakesIndirectLight) {

    const std::filesystem::path dir = test::make_temp_dir("view-window-indirect");
    const std::filesystem::path scene_path = dir / "cornell.gltf";
    ASSERT_TRUE(write_scene_gltf(make_cornell_emissive_scene(), scene_path).ok());
    std::ofstream(dir / "script.txt") << "bake\nquit\n";
    const std::string command = "xvfb-run -a " + (test::bin_dir() / "editor_client").string() + " view " +
                                scene_path.string() + " --spawn-server --area-lights 256 --indirect radiosity" +
                                " --patch-size 0.5 --script " + (dir / "script.txt").string() +
                                " --size 96x72 --validation";
    const auto [status, text] = run_logged(command, dir / "view.log");
    ASSERT_EQ(status, 0) << text;
    EXPECT_NE(text.find("0 validation messages"), std::string::npos) << text;
    const size_t at = text.find("bake: 0 lights -> ");
    ASSERT_NE(at, std::string::npos) << text;
    const unsigned long nodes = std::stoul(text.substr(at + std::string("bake: 0 lights -> ").size()));
    EXPECT_GT(nodes, 2u * 256u) << "no patches beside the 256 area-light samples: " << text;
    std::filesystem::remove_all(dir);
}

// The Server panel in a scripted session: it asks the server `view` bakes with
// for its status (the log says what the panel said at the end), and says in
// one line when nothing answers at that address.
TEST_F(ViewWindow, XvfbServerPanelShowsTheServersStatus) {
    const std::filesystem::path dir = test::make_temp_dir("view-window-server-panel");
    const std::filesystem::path scene_path = dir / "room.gltf";
    ASSERT_TRUE(write_scene_gltf(test::lit_room(5), scene_path).ok());
    std::ofstream(dir / "script.txt") << "wait-frames 2\nquit\n";
    auto view_with_server = [&](const std::string& address) {
        return run_logged("xvfb-run -a " + (test::bin_dir() / "editor_client").string() + " view " +
                              scene_path.string() + " --server " + address + " --script " +
                              (dir / "script.txt").string() + " --size 96x72 --validation",
                          dir / "view.log");
    };

    auto server = ServerProcess::spawn_with((test::bin_dir() / "lightmass_server").string(),
                                            {"--listen", "127.0.0.1:0", "--max-connections", "7", "--quiet"});
    ASSERT_TRUE(server.ok()) << server.error();
    const auto [status, text] = view_with_server(server.value()->address());
    ASSERT_EQ(status, 0) << text;
    EXPECT_NE(text.find("0 validation messages"), std::string::npos) << text;
    EXPECT_NE(text.find(std::string("server panel: lightmass_server ") + kVersion + ", up "), std::string::npos)
        << text;
    EXPECT_NE(text.find("server panel: connections: 1 of 7"), std::string::npos) << text;
    EXPECT_NE(text.find("server panel: bakes: 0 running, 0 queued, 0 streaming"), std::string::npos) << text;

    uint16_t closed = 0;
    {
        asio::io_context io;
        tcp::acceptor acceptor(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
        closed = acceptor.local_endpoint().port();
    }
    const std::string nobody = "127.0.0.1:" + std::to_string(closed);
    const auto [unreachable_status, unreachable] = view_with_server(nobody);
    ASSERT_EQ(unreachable_status, 0) << unreachable;
    EXPECT_NE(unreachable.find("server panel: server " + nobody + " unreachable: cannot connect to "),
              std::string::npos)
        << unreachable;
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lc::client
