// The editor's real-time mode: whole frames every tick (no tiles), the
// accumulated history as the refinement (`wait-refined` waits until the
// spatial filter is gone), the real-time cut as a validated view control and
// script command, and `editor_client view --mode realtime` under xvfb-run with
// a scripted session that switches between the real-time and the
// deterministic mode.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/script_runner.h"
#include "editor_client/render/output/image_io.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/window/editor_loop.h"
#include "editor_client/window/headless_window.h"
#include "lightcuts/device/limits.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

std::unique_ptr<EditorSession> room_in_realtime(const std::filesystem::path& dir) {
    Scene scene = test::lit_room(11);
    const RenderCamera camera = camera_from_scene(scene.cameras.at(0));
    const std::filesystem::path tree = test::write_tree_dump(scene, dir);
    auto session = std::make_unique<EditorSession>(std::move(scene));
    EXPECT_TRUE(session->view_settings().set_camera(camera));
    EXPECT_TRUE(session->import_tree_dump(tree).ok());
    EXPECT_TRUE(session->view_settings().set_mode("realtime").ok());
    return session;
}

TEST(EditorRealtime, CutIsAValidatedViewControl) {
    EditorSession session(test::lit_room(3));
    EXPECT_TRUE(session.view_settings().set_realtime_cut(8).ok());
    EXPECT_EQ(session.view().realtime_cut, 8u);
    for (uint32_t bad : {0u, 33u}) {
        const Status refused = session.view_settings().set_realtime_cut(bad);
        ASSERT_FALSE(refused.ok()) << bad;
        EXPECT_NE(refused.error().find("real-time cut"), std::string::npos) << refused.error();
        EXPECT_EQ(session.view().realtime_cut, 8u) << "a refused value leaves the view as it was";
    }
    Result<std::optional<EditorCommand>> parsed = parse_editor_command("realtime-cut 12");
    ASSERT_TRUE(parsed.ok()) << parsed.error();
    ASSERT_TRUE(parsed->has_value());
    EXPECT_EQ(std::get<cmd::RealtimeCut>(**parsed).nodes, 12u);
    EXPECT_FALSE(parse_editor_command("realtime-cut").ok());
}

TEST(EditorRealtime, ShadowRayBudgetIsAValidatedViewControl) {
    EditorSession session(test::lit_room(3));
    EXPECT_EQ(session.view().realtime_rays, kDefaultRealtimeRays);
    EXPECT_TRUE(session.view_settings().set_realtime_rays(0).ok()) << "0: one ray per cut node";
    EXPECT_TRUE(session.view_settings().set_realtime_rays(2).ok());
    const Status refused = session.view_settings().set_realtime_rays(kMaxStochasticRays + 1);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().find("shadow rays"), std::string::npos) << refused.error();
    EXPECT_EQ(session.view().realtime_rays, 2u) << "a refused value leaves the view as it was";
    EXPECT_EQ(render_settings_for(session.view(), 4, 4, true).realtime_rays, 2u);
    Result<std::optional<EditorCommand>> parsed = parse_editor_command("realtime-rays 1");
    ASSERT_TRUE(parsed.ok()) << parsed.error();
    ASSERT_TRUE(parsed->has_value());
    EXPECT_EQ(std::get<cmd::RealtimeRays>(**parsed).rays, 1u);
    EXPECT_FALSE(parse_editor_command("realtime-rays").ok());
    EXPECT_EQ(realtime_ray_budget(16, 0), 16u);
    EXPECT_EQ(realtime_ray_budget(16, 4), 4u);
    EXPECT_EQ(realtime_ray_budget(2, 4), 2u) << "a cut smaller than the budget traces a ray per node";
}

TEST(EditorRealtime, HeadlessLoopAccumulatesWholeFramesUntilRefined) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    const std::filesystem::path dir = test::make_temp_dir("editor-realtime");
    std::unique_ptr<EditorSession> session = room_in_realtime(dir);
    Result<std::vector<ScriptLine>> lines = parse_editor_script(
        "realtime-cut 8\nwait-refined\nsave-view " + (dir / "refined.pfm").string() + "\nquit\n", "rt.txt");
    ASSERT_TRUE(lines.ok()) << lines.error();
    ScriptRunner script(std::move(lines).value(), "rt.txt");
    HeadlessWindow window(64, 48);
    EditorLoopOptions options;
    options.width = 64;
    options.height = 48;
    options.script = &script;
    options.progressive = true;  // the real-time mode bypasses the tiles
    Result<EditorLoopSummary> summary = run_editor_loop(window, *context, *session, options);
    ASSERT_TRUE(summary.ok()) << summary.error();
    EXPECT_EQ(script.state(), ScriptState::kQuit) << script.error();
    EXPECT_EQ(summary->last_mode, RenderMode::kRealtime);
    EXPECT_TRUE(summary->refinement_events.empty()) << "no tiles in the real-time mode";
    // 16 frames of history before the view counts as refined, one frame a tick.
    EXPECT_GE(summary->frames, 16u);
    EXPECT_EQ(summary->last_frame.width, 64u) << "whole frames at the full size";
    ASSERT_TRUE(summary->last_frame.realtime_frames);
    EXPECT_GE(*summary->last_frame.realtime_frames, 16u);
    EXPECT_EQ(context->validation_message_count(), 0u);
    Result<FloatImage> refined = read_pfm(dir / "refined.pfm");
    ASSERT_TRUE(refined.ok()) << refined.error();
    double sum = 0.0;
    for (float v : refined->rgb) sum += v;
    EXPECT_GT(sum, 0.0) << "the refined view is lit";
    std::filesystem::remove_all(dir);
}

TEST(EditorRealtime, XvfbViewSwitchesBetweenRealtimeAndLightcuts) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed";
    std::unique_ptr<vk::Context> probe;
    LC_REQUIRE_VULKAN(probe);
    probe.reset();
    const std::filesystem::path dir = test::make_temp_dir("editor-realtime-xvfb");
    const Scene scene = test::lit_room(11);
    const std::filesystem::path scene_path = dir / "room.gltf";
    ASSERT_TRUE(write_scene_gltf(scene, scene_path).ok());
    const std::filesystem::path tree = test::write_tree_dump(scene, dir);
    const std::filesystem::path script_path = dir / "script.txt";
    {
        std::ofstream out(script_path);
        out << "wait-refined\nscreenshot " << (dir / "realtime.png").string() << "\n"
            << "mode lightcuts\nwait-refined\nmode realtime\nrealtime-cut 4\nwait-frames 2\nrealtime-rays 1\n"
            << "wait-frames 2\nquit\n";
    }
    const std::filesystem::path log = dir / "view.log";
    const std::string command = "xvfb-run -a " + (test::bin_dir() / "editor_client").string() + " view " +
                                scene_path.string() + " --tree " + tree.string() +
                                " --mode realtime --size 96x72 --exposure 1 --validation --script " +
                                script_path.string() + " > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    const std::string text = test::read_text(log);
    ASSERT_EQ(status, 0) << text;
    EXPECT_NE(text.find("last in realtime mode"), std::string::npos) << text;
    EXPECT_NE(text.find("0 validation messages"), std::string::npos) << text;
    test::expect_not_blank(test::read_image(dir / "realtime.png"), "real-time screenshot");
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lc::client
