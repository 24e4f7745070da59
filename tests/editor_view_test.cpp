// The editor's window loop driven by a `--script` against a real local
// lightmass_server: in process with a headless window, and as the
// `editor_client view` command in a real GLFW window under xvfb-run. Checks
// the screenshots (not blank, changed by an add-light + bake, lightcuts close
// to the reference) and the saved glTF (light count and values).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "editor_client/bake/server_process.h"
#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/script_runner.h"
#include "editor_client/render/output/image_io.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "editor_client/window/editor_loop.h"
#include "editor_client/window/headless_window.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

std::string server_binary() {
    return (test::bin_dir() / "lightmass_server").string();
}

// The script every test runs: a screenshot of the starting lights, two added
// lights, a bake, then reference, lightcuts and cuts screenshots and a save.
std::string editor_script(const std::filesystem::path& dir) {
    return "# scripted editor session\n"
           "screenshot " +
           (dir / "before.png").string() +
           "\n"
           "add-light point 0.5 2.2 0.5 1 0.6 0.3 60 6\n"
           "add-light point -3 1.2 2.5 0.2 0.5 1 35\n"
           "\n"
           "bake\n"
           "screenshot " +
           (dir / "reference.png").string() +
           "\n"
           "mode lightcuts\n"
           "criterion radius\n"
           "screenshot " +
           (dir / "lightcuts.png").string() +
           "\n"
           "mode cuts\n"
           "screenshot " +
           (dir / "cuts.png").string() +
           "\n"
           "save " +
           (dir / "saved.gltf").string() +
           "\n"
           "quit\n";
}

// Mean absolute difference per RGB channel, in 8-bit levels.
double mean_difference(const Rgba8Image& a, const Rgba8Image& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    if (a.rgba.size() != b.rgba.size() || a.rgba.empty()) return 1e9;
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
        ++count;
    }
    return sum / double(count);
}

// What every run of the script must have produced in `dir`.
void check_outputs(const std::filesystem::path& dir, uint32_t width, uint32_t height) {
    const Rgba8Image before = test::read_image(dir / "before.png");
    const Rgba8Image reference = test::read_image(dir / "reference.png");
    const Rgba8Image lightcuts = test::read_image(dir / "lightcuts.png");
    const Rgba8Image cuts = test::read_image(dir / "cuts.png");
    for (const Rgba8Image* image : {&before, &reference, &lightcuts, &cuts}) {
        EXPECT_EQ(image->width, width);
        EXPECT_EQ(image->height, height);
    }
    test::expect_not_blank(before, "before.png");
    test::expect_not_blank(reference, "reference.png");
    test::expect_not_blank(lightcuts, "lightcuts.png");
    test::expect_not_blank(cuts, "cuts.png", 3);
    // The two added lights are bright: the image must change visibly, far
    // more than lightcuts differs from the exact reference of the same lights.
    const double added = mean_difference(before, reference);
    const double approximation = mean_difference(reference, lightcuts);
    EXPECT_GT(added, 3.0) << "adding lights and baking did not change the view";
    EXPECT_LT(approximation, 3.0) << "lightcuts is far from the reference";
    EXPECT_LT(approximation * 2.0, added);
    // The cuts view colours cuts, not shading: unlike the lightcuts image.
    EXPECT_GT(mean_difference(lightcuts, cuts), 10.0);

    Result<Scene> saved = load_scene(dir / "saved.gltf");
    ASSERT_TRUE(saved.ok()) << saved.error();
    ASSERT_EQ(saved->lights.size(), 14u);
    const SceneLight& first = saved->lights[12];
    EXPECT_EQ(first.type, LightType::kPoint);
    EXPECT_NEAR(first.position.x, 0.5f, 1e-5f);
    EXPECT_NEAR(first.position.y, 2.2f, 1e-5f);
    EXPECT_NEAR(first.position.z, 0.5f, 1e-5f);
    EXPECT_NEAR(first.color.r, 1.0f, 1e-5f);
    EXPECT_NEAR(first.color.g, 0.6f, 1e-5f);
    EXPECT_NEAR(first.color.b, 0.3f, 1e-5f);
    EXPECT_NEAR(first.intensity, 60.0f, 1e-3f);
    EXPECT_NEAR(first.range, 6.0f, 1e-5f);
    const SceneLight& second = saved->lights[13];
    EXPECT_NEAR(second.position.x, -3.0f, 1e-5f);
    EXPECT_NEAR(second.color.b, 1.0f, 1e-5f);
    EXPECT_NEAR(second.intensity, 35.0f, 1e-3f);
    EXPECT_EQ(second.range, 0.0f);
}

TEST(EditorView, HeadlessLoopRunsTheScriptAgainstALocalServer) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    auto server =
        ServerProcess::spawn_with(server_binary(), {"--quiet", "--listen", "127.0.0.1:0", "--threads", "2"});
    ASSERT_TRUE(server.ok()) << server.error();

    const std::filesystem::path dir = test::make_temp_dir("editor-view");
    Result<std::vector<ScriptLine>> lines = parse_editor_script(editor_script(dir), "test.txt");
    ASSERT_TRUE(lines.ok()) << lines.error();
    ScriptRunner script(std::move(lines).value(), "test.txt");

    EditorSessionOptions session_options;
    session_options.bake.server = (*server)->address();
    session_options.bake.timeout_seconds = 120.0;
    Scene scene = test::lit_room(5);
    const RenderCamera camera = camera_from_scene(scene.cameras.at(0));
    EditorSession session(std::move(scene), session_options);
    ASSERT_TRUE(session.view_settings().set_camera(camera));

    HeadlessWindow window(96, 72);
    EditorLoopOptions options;
    options.width = 96;
    options.height = 72;
    options.script = &script;
    options.screenshot = dir / "final.png";
    Result<EditorLoopSummary> summary = run_editor_loop(window, *context, session, options);
    ASSERT_TRUE(summary.ok()) << summary.error();
    EXPECT_EQ(summary->script_state, ScriptState::kQuit) << script.error();
    EXPECT_EQ(summary->screenshots, 5u);  // four scripted, one at the end
    EXPECT_GE(summary->frames, 1u);       // frames were drawn while the bake ran
    EXPECT_TRUE(session.tree_matches_scene());
    EXPECT_NE(window.title().find("lightcuts editor"), std::string::npos) << window.title();
    EXPECT_EQ(context->validation_message_count(), 0u);
    check_outputs(dir, 96, 72);
    std::filesystem::remove_all(dir);
}

TEST(EditorView, AFailingScriptLineStopsTheLoopWithItsLineNumber) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    Result<std::vector<ScriptLine>> lines =
        parse_editor_script("mode reference\nremove-light 40\nquit\n", "bad.txt");
    ASSERT_TRUE(lines.ok()) << lines.error();
    ScriptRunner script(std::move(lines).value(), "bad.txt");
    EditorSession session(test::lit_room(5));
    HeadlessWindow window(32, 32);
    EditorLoopOptions options;
    options.width = options.height = 32;
    options.script = &script;
    Result<EditorLoopSummary> summary = run_editor_loop(window, *context, session, options);
    ASSERT_FALSE(summary.ok());
    EXPECT_EQ(summary.error().rfind("bad.txt:2: ", 0), 0u) << summary.error();
    EXPECT_EQ(session.scene().lights.size(), 12u);
}

TEST(EditorView, AutoExposureIsSetFromTheFirstFullSizeFrameUnlessGiven) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    const Scene scene = test::overexposed_lit_room(5);
    const RenderCamera camera = camera_from_scene(scene.cameras.at(0));
    auto run = [&](bool automatic, const std::string& script_text) {
        Result<std::vector<ScriptLine>> lines = parse_editor_script(script_text, "exposure.txt");
        EXPECT_TRUE(lines.ok()) << lines.error();
        ScriptRunner script(std::move(lines).value(), "exposure.txt");
        EditorSession session(scene);
        EXPECT_TRUE(session.view_settings().set_camera(camera));
        HeadlessWindow window(48, 36);
        EditorLoopOptions options;
        options.width = 48;
        options.height = 36;
        options.frames = 3;
        options.adaptive_resolution = false;
        options.auto_exposure = automatic;
        options.script = &script;
        Result<EditorLoopSummary> summary = run_editor_loop(window, *context, session, options);
        EXPECT_TRUE(summary.ok()) << summary.error();
        return session.view().exposure;
    };
    const float automatic = run(true, "mode reference\n");
    EXPECT_GT(automatic, 0.0f);
    EXPECT_LT(automatic, 0.01f) << "1000x brighter lights need a far smaller exposure";
    EXPECT_EQ(run(false, "mode reference\n"), 1.0f);        // --exposure given
    EXPECT_EQ(run(true, "exposure 2.5\n"), 2.5f);            // set by the script first
    EXPECT_EQ(context->validation_message_count(), 0u);
}

TEST(EditorView, EditsReachTheRendererWithoutABake) {
    // Without a server the editor still shows edited lights (reference mode).
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    const std::filesystem::path dir = test::make_temp_dir("editor-edits");
    const std::string text = "screenshot " + (dir / "a.png").string() +
                             "\n"
                             "add-light point 0 1.5 0 1 1 1 80 8\n"
                             "mode lightcuts\n"  // accepted; shown as reference until a bake
                             "screenshot " +
                             (dir / "b.png").string() +
                             "\n"
                             "undo\n"
                             "screenshot " +
                             (dir / "c.png").string() + "\nquit\n";
    Result<std::vector<ScriptLine>> lines = parse_editor_script(text, "edits.txt");
    ASSERT_TRUE(lines.ok()) << lines.error();
    ScriptRunner script(std::move(lines).value(), "edits.txt");
    Scene scene = test::lit_room(5);
    const RenderCamera camera = camera_from_scene(scene.cameras.at(0));
    EditorSession session(std::move(scene));
    ASSERT_TRUE(session.view_settings().set_camera(camera));
    HeadlessWindow window(64, 48);
    EditorLoopOptions options;
    options.width = 64;
    options.height = 48;
    options.script = &script;
    Result<EditorLoopSummary> summary = run_editor_loop(window, *context, session, options);
    ASSERT_TRUE(summary.ok()) << summary.error();
    const Rgba8Image a = test::read_image(dir / "a.png");
    const Rgba8Image b = test::read_image(dir / "b.png");
    const Rgba8Image c = test::read_image(dir / "c.png");
    EXPECT_GT(mean_difference(a, b), 3.0);
    EXPECT_EQ(mean_difference(a, c), 0.0);  // undo restores the exact image
    std::filesystem::remove_all(dir);
}

TEST(EditorView, XvfbEditorCommandRunsTheScriptWithASpawnedServer) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed";
    std::unique_ptr<vk::Context> probe;
    LC_REQUIRE_VULKAN(probe);
    probe.reset();

    const std::filesystem::path dir = test::make_temp_dir("editor-xvfb");
    const std::filesystem::path scene_path = dir / "room.gltf";
    ASSERT_TRUE(write_scene_gltf(test::lit_room(5), scene_path).ok());
    const std::filesystem::path script_path = dir / "script.txt";
    {
        std::ofstream out(script_path);
        out << editor_script(dir);
    }
    const std::filesystem::path log = dir / "editor.log";
    const std::string command = "LC_SERVER_BIN=" + server_binary() + " xvfb-run -a " +
                                (test::bin_dir() / "editor_client").string() + " view " +
                                scene_path.string() + " --spawn-server --size 96x72 --script " +
                                script_path.string() + " --validation > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    ASSERT_EQ(status, 0) << text.str();
    EXPECT_NE(text.str().find("0 validation messages"), std::string::npos) << text.str();
    check_outputs(dir, 96, 72);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lc::client
