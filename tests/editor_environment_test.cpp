// The editor with an environment: Build Lighting from the window sends the
// scene's emissive surfaces and the sky with the lights, and the view shows
// the sky as its background; the `view` command takes --sky like bake and
// render, and otherwise the glTF's own environment.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "editor_client/bake/server_process.h"
#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/script_runner.h"
#include "editor_client/render/output/image_io.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "editor_client/window/editor_loop.h"
#include "editor_client/window/headless_window.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

std::string server_binary() { return (test::bin_dir() / "lightmass_server").string(); }

std::shared_ptr<const Environment> afternoon_sky() {
    auto environment = std::make_shared<Environment>();
    environment->sky = SkyParameters{30.0f, 60.0f, 3.0f};
    environment->intensity = 0.05f;  // the sky near 0.25 at exposure 1
    return environment;
}

// Pixels of the top row that show a blue sky (blue clearly above red).
size_t sky_pixels_in_top_row(const Rgba8Image& image) {
    size_t sky = 0;
    for (uint32_t x = 0; x < image.width && !image.rgba.empty(); ++x) {
        const uint8_t* p = &image.rgba[size_t(x) * 4];
        sky += p[2] > p[0] + 10 ? 1u : 0u;
    }
    return sky;
}

size_t black_pixels_in_top_row(const Rgba8Image& image) {
    size_t black = 0;
    for (uint32_t x = 0; x < image.width && !image.rgba.empty(); ++x) {
        const uint8_t* p = &image.rgba[size_t(x) * 4];
        black += p[0] == 0 && p[1] == 0 && p[2] == 0 ? 1u : 0u;
    }
    return black;
}

TEST(EditorEnvironment, ScriptedBakeFromTheWindowSendsTheEmissivePanelAndTheSky) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    auto server =
        ServerProcess::spawn_with(server_binary(), {"--quiet", "--listen", "127.0.0.1:0", "--threads", "2"});
    ASSERT_TRUE(server.ok()) << server.error();

    const std::filesystem::path dir = test::make_temp_dir("editor-environment");
    const std::string script_text = "camera 0 1 7 0 1 0 50\nbake\nmode lightcuts\nscreenshot " +
                                    (dir / "sky.png").string() + "\nquit\n";
    Result<std::vector<ScriptLine>> lines = parse_editor_script(script_text, "sky.txt");
    ASSERT_TRUE(lines.ok()) << lines.error();
    ScriptRunner script(std::move(lines).value(), "sky.txt");

    EditorSessionOptions session_options;
    session_options.bake.server = (*server)->address();
    session_options.bake.timeout_seconds = 120.0;
    session_options.bake.area_lights = 256;
    session_options.bake.environment = afternoon_sky();
    session_options.bake.environment_lights = 256;
    Scene scene = make_cornell_emissive_scene();
    ASSERT_TRUE(scene.lights.empty());  // lit by its panel alone
    EditorSession session(std::move(scene), session_options);

    HeadlessWindow window(64, 48);
    EditorLoopOptions options;
    options.width = 64;
    options.height = 48;
    options.adaptive_resolution = false;
    options.auto_exposure = false;  // exposure 1
    options.script = &script;
    Result<EditorLoopSummary> summary = run_editor_loop(window, *context, session, options);
    ASSERT_TRUE(summary.ok()) << summary.error();
    EXPECT_EQ(summary->script_state, ScriptState::kQuit) << script.error();
    ASSERT_TRUE(session.baking().last_bake() && session.baking().last_bake()->succeeded)
        << (session.baking().last_bake() ? session.baking().last_bake()->error : "no bake");

    // The tree holds the panel's area lights (oriented) and the sky's (directional).
    std::shared_ptr<const LightTree> tree = session.baking().tree();
    ASSERT_TRUE(tree && !tree->empty());
    size_t area = 0, sky = 0;
    for (const LightTreeNode& node : tree->nodes) {
        if (!node.is_leaf()) continue;
        area += node.type == LightType::kOriented ? 1u : 0u;
        sky += node.type == LightType::kDirectional ? 1u : 0u;
    }
    EXPECT_GT(area, 100u);
    EXPECT_GT(sky, 100u);
    EXPECT_TRUE(session.tree_matches_scene());

    // Above the box the window shows the sky.
    const Rgba8Image shot = test::read_image(dir / "sky.png");
    EXPECT_EQ(sky_pixels_in_top_row(shot), shot.width);
    EXPECT_EQ(context->validation_message_count(), 0u);
    std::filesystem::remove_all(dir);
}

TEST(EditorEnvironment, ViewTakesTheSkyFlagOrTheGltfsEnvironment) {
    std::unique_ptr<vk::Context> probe;
    LC_REQUIRE_VULKAN(probe);
    probe.reset();
    const std::filesystem::path dir = test::make_temp_dir("view-environment");
    Scene plain = make_cornell_emissive_scene();
    ASSERT_TRUE(write_scene_gltf(plain, dir / "plain.gltf"));
    Scene named = plain;
    named.environment = afternoon_sky();
    ASSERT_TRUE(write_scene_gltf(named, dir / "named.gltf"));

    auto view = [&](const std::string& scene, const std::string& flags, const std::string& shot) {
        const std::filesystem::path log = dir / (shot + ".log");
        const std::string command = (test::bin_dir() / "editor_client").string() + " view " +
                                    (dir / scene).string() + " --headless --no-progressive --size 64x48" +
                                    " --camera 0,1,7,0,1,0,50 --exposure 1 --frames 2 --validation --screenshot " +
                                    (dir / shot).string() + " " + flags + " > " + log.string() + " 2>&1";
        const int status = std::system(command.c_str());
        std::ifstream in(log);
        std::stringstream text;
        text << in.rdbuf();
        EXPECT_EQ(status, 0) << text.str();
        EXPECT_NE(text.str().find(" 0 validation messages"), std::string::npos) << text.str();
        return test::read_image(dir / shot);
    };
    const Rgba8Image black = view("plain.gltf", "", "plain.png");
    EXPECT_EQ(black_pixels_in_top_row(black), black.width);
    const Rgba8Image flagged = view("plain.gltf", "--sky 30,60,3 --environment-intensity 0.05", "flag.png");
    EXPECT_EQ(sky_pixels_in_top_row(flagged), flagged.width);
    const Rgba8Image from_file = view("named.gltf", "", "named.png");
    EXPECT_EQ(sky_pixels_in_top_row(from_file), from_file.width);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lc::client
