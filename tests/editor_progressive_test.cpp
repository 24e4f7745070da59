// The progressive view: its schedule (tiles, passes, the budget per frame) on
// its own, the editor loop refining headless, and `editor_client view` under
// xvfb-run with a --script that moves the camera and changes the error ratio
// while the image refines: each input restarts the refinement in the frame
// it arrives, and the finished image equals a whole-frame render of the view.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/progressive_refinement.h"
#include "editor_client/editor/script_runner.h"
#include "editor_client/render/output/image_io.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/window/editor_loop.h"
#include "editor_client/window/headless_window.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

// Every pixel of a width x height image, covered once by `tiles`.
void expect_exact_cover(const std::vector<PixelRegion>& tiles, uint32_t width, uint32_t height) {
    std::vector<int> covered(size_t(width) * height, 0);
    for (const PixelRegion& t : tiles) {
        ASSERT_LE(t.x + t.width, width);
        ASSERT_LE(t.y + t.height, height);
        for (uint32_t y = t.y; y < t.y + t.height; ++y)
            for (uint32_t x = t.x; x < t.x + t.width; ++x) ++covered[size_t(y) * width + x];
    }
    EXPECT_EQ(std::count(covered.begin(), covered.end(), 1), ptrdiff_t(covered.size()));
}

TEST(ProgressiveRefinement, TilesCoverTheImageOnceCentreFirstOnWorkgroupBoundaries) {
    const std::vector<PixelRegion> tiles = tiles_centre_first(100, 70, 16);
    EXPECT_EQ(tiles.size(), 7u * 5u);
    expect_exact_cover(tiles, 100, 70);
    for (const PixelRegion& t : tiles) {
        EXPECT_EQ(t.x % 16, 0u);
        EXPECT_EQ(t.y % 16, 0u);
    }
    // The first tile holds the centre; the last is a corner.
    EXPECT_TRUE(tiles.front().x <= 50 && 50 < tiles.front().x + tiles.front().width);
    EXPECT_TRUE(tiles.front().y <= 35 && 35 < tiles.front().y + tiles.front().height);
    const PixelRegion& last = tiles.back();
    EXPECT_TRUE((last.x == 0 || last.x == 96) && (last.y == 0 || last.y == 64));
}

TEST(ProgressiveRefinement, RefinesACoarsePassThenTheFullImage) {
    ProgressiveRefinement refinement(100, 70, 8, {.frame_budget_ms = 30.0, .tile_size = 16});
    refinement.restart(4);
    ASSERT_EQ(refinement.passes(), 2u);
    std::vector<std::vector<PixelRegion>> passes(2);
    uint32_t frames = 0;
    bool first_of_pass[2] = {false, false};
    while (std::optional<TileBatch> batch = refinement.next_batch()) {
        ++frames;
        ASSERT_LT(batch->pass, 2u);
        EXPECT_EQ(batch->divisor, batch->pass == 0 ? 4u : 1u);
        EXPECT_EQ(batch->width, batch->pass == 0 ? 25u : 100u);
        EXPECT_EQ(batch->height, batch->pass == 0 ? 18u : 70u);
        if (batch->new_image) {
            EXPECT_FALSE(first_of_pass[batch->pass]) << "one new image per pass";
            EXPECT_TRUE(passes[batch->pass].empty());
            first_of_pass[batch->pass] = true;
        }
        EXPECT_EQ(batch->tiles.size(), 1u) << "nothing reported yet: one tile a frame";
        passes[batch->pass].insert(passes[batch->pass].end(), batch->tiles.begin(), batch->tiles.end());
    }
    EXPECT_TRUE(refinement.complete());
    EXPECT_EQ(refinement.percent(), 100.0);
    expect_exact_cover(passes[0], 25, 18);
    expect_exact_cover(passes[1], 100, 70);
    EXPECT_EQ(frames, passes[0].size() + passes[1].size());

    // A restart starts from the coarse pass again; divisor 1 has no coarse pass.
    refinement.restart(1);
    EXPECT_EQ(refinement.passes(), 1u);
    EXPECT_FALSE(refinement.complete());
    EXPECT_EQ(refinement.percent(), 0.0);
    EXPECT_TRUE(refinement.next_batch()->new_image);
}

TEST(ProgressiveRefinement, TilesPerFrameFollowTheMeasuredCostAndTheBudget) {
    ProgressiveRefinement refinement(512, 512, 8, {.frame_budget_ms = 30.0, .tile_size = 16});
    EXPECT_EQ(refinement.tiles_per_frame(), 1u);
    std::optional<TileBatch> batch = refinement.next_batch();
    ASSERT_TRUE(batch);
    // 256 pixels in 2.56 ms: 0.01 ms a pixel, 2.56 ms a tile, 11 tiles in 30 ms.
    refinement.report(*batch, 2.56);
    EXPECT_DOUBLE_EQ(refinement.ms_per_pixel(), 0.01);
    EXPECT_EQ(refinement.tiles_per_frame(), 11u);
    batch = refinement.next_batch();
    ASSERT_TRUE(batch);
    EXPECT_EQ(batch->tiles.size(), 11u);
    // Tiles that turn out dearer shrink the next batches, smoothed.
    refinement.report(*batch, 11 * 256 * 0.1);
    EXPECT_NEAR(refinement.ms_per_pixel(), 0.6 * 0.01 + 0.4 * 0.1, 1e-12);
    EXPECT_EQ(refinement.tiles_per_frame(), 2u);
    // Never fewer than one tile, however dear.
    refinement.report(*batch, 1e9);
    EXPECT_EQ(refinement.tiles_per_frame(), 1u);
}

TEST(ProgressiveRefinement, APassStartsWithTilesThatFitTheBudget) {
    ProgressiveRefinement refinement(64, 64, 8, {.frame_budget_ms = 30.0, .tile_size = 16});
    refinement.restart(2);
    EXPECT_EQ(refinement.tile_side(), 16u) << "nothing learned yet";
    // 0.2 ms a pixel: a 16-pixel tile takes 51 ms, an 8-pixel one 12.8 ms.
    std::optional<TileBatch> batch = refinement.next_batch();
    ASSERT_TRUE(batch);
    refinement.report(*batch, 0.2 * double(batch->pixels()));
    while (refinement.pass() == 0) ASSERT_TRUE(refinement.next_batch());
    EXPECT_EQ(refinement.tile_side(), 8u);
    EXPECT_EQ(refinement.tiles_per_frame(), 2u);
    batch = refinement.next_batch();
    ASSERT_TRUE(batch);
    EXPECT_EQ(batch->tiles.size(), 2u);
    EXPECT_EQ(batch->tiles.front().width, 8u);
}

std::vector<float> read_radiance(const std::filesystem::path& path) {
    Result<FloatImage> image = read_pfm(path);
    EXPECT_TRUE(image.ok()) << path << ": " << (image.ok() ? "" : image.error());
    return image.ok() ? image->rgb : std::vector<float>{};
}

// The refined image against a whole-frame render of the same view: equal
// within float tolerance, and lit (not a black or unfinished image).
void expect_same_radiance(const std::filesystem::path& refined, const std::filesystem::path& whole) {
    const std::vector<float> a = read_radiance(refined);
    const std::vector<float> b = read_radiance(whole);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    size_t lit = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_TRUE(std::isfinite(a[i])) << i;
        EXPECT_NEAR(a[i], b[i], 1e-5f + 1e-5f * std::abs(b[i])) << "component " << i;
        lit += b[i] > 0.0f ? 1 : 0;
    }
    EXPECT_GT(lit, a.size() / 4);
}

// A camera a little to the side of the scene's own, as the script spells it.
std::string moved_camera_line(const RenderCamera& camera) {
    char line[256];
    std::snprintf(line, sizeof line, "camera %g %g %g %g %g %g %g\n", camera.eye.x + 0.7f, camera.eye.y + 0.2f,
                  camera.eye.z, camera.target.x, camera.target.y, camera.target.z,
                  camera.yfov * 180.0f / 3.14159265f);
    return line;
}

// Two frames in, the camera moves; a frame later the error ratio changes; then
// the script waits for the refined image and saves it beside a whole frame.
std::string input_while_refining_script(const RenderCamera& camera, const std::filesystem::path& dir) {
    return "wait-frames 2\n" + moved_camera_line(camera) +
           "wait-frames 1\n"
           "error-ratio 0.01\n"
           "wait-refined\n"
           "save-view " +
           (dir / "refined.pfm").string() +
           "\n"
           "screenshot " +
           (dir / "whole.pfm").string() + "\nquit\n";
}

// With a budget far below one tile's cost every frame takes one tile: a 96x72
// view takes dozens of frames, and the input arrives long before the end.
constexpr double kOneTileBudgetMs = 1e-3;

struct ScriptedRun {
    Result<EditorLoopSummary> summary = make_error("not run");
    ScriptState script_state = ScriptState::kRunning;
    std::string script_error;
};

// The progressive loop headless at width x height, one tile a frame, driven by `script_text`.
ScriptedRun run_progressive_script(const vk::Context& context, EditorSession& session,
                                   const std::string& script_text, uint32_t width, uint32_t height,
                                   bool auto_exposure) {
    ScriptedRun run;
    Result<std::vector<ScriptLine>> lines = parse_editor_script(script_text, "progressive.txt");
    if (!lines) {
        run.summary = make_error(lines.error());
        return run;
    }
    ScriptRunner script(std::move(lines).value(), "progressive.txt");
    HeadlessWindow window(width, height);
    EditorLoopOptions options;
    options.width = width;
    options.height = height;
    options.script = &script;
    options.auto_exposure = auto_exposure;
    options.progressive = true;
    options.refinement.frame_budget_ms = kOneTileBudgetMs;
    run.summary = run_editor_loop(window, context, session, options);
    run.script_state = script.state();
    run.script_error = script.error();
    return run;
}

// The lit room with its tree imported (a dump written in `dir`), at its own
// camera, in lightcuts mode.
std::unique_ptr<EditorSession> room_in_lightcuts(const std::filesystem::path& dir) {
    Scene scene = test::lit_room(11);
    const RenderCamera camera = camera_from_scene(scene.cameras.at(0));
    const std::filesystem::path tree = test::write_tree_dump(scene, dir);
    auto session = std::make_unique<EditorSession>(std::move(scene));
    EXPECT_TRUE(session->view_settings().set_camera(camera));
    EXPECT_TRUE(session->import_tree_dump(tree).ok());
    session->view_settings().set_mode(RenderMode::kLightcuts);
    return session;
}

TEST(EditorProgressive, HeadlessLoopRestartsOnInputAndEndsWithTheWholeFrame) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    const std::filesystem::path dir = test::make_temp_dir("editor-progressive");
    std::unique_ptr<EditorSession> owned = room_in_lightcuts(dir);
    EditorSession& session = *owned;
    const RenderCamera camera = session.view().camera;

    const ScriptedRun run =
        run_progressive_script(*context, session, input_while_refining_script(camera, dir), 96, 72, false);
    const Result<EditorLoopSummary>& summary = run.summary;
    ASSERT_TRUE(summary.ok()) << summary.error();
    EXPECT_EQ(run.script_state, ScriptState::kQuit) << run.script_error;

    using Kind = RefinementEvent::Kind;
    const std::vector<RefinementEvent>& events = summary->refinement_events;
    ASSERT_EQ(events.size(), 4u);
    EXPECT_EQ(events[0].kind, Kind::kStarted);
    EXPECT_EQ(events[0].frame, 0u);
    // Each input restarts the image in the frame the script ran it, unfinished.
    EXPECT_EQ(events[1].kind, Kind::kRestarted);
    EXPECT_EQ(events[1].frame, 2u);
    EXPECT_EQ(events[2].kind, Kind::kRestarted);
    EXPECT_EQ(events[2].frame, 3u);
    for (int i : {1, 2}) {
        EXPECT_LT(events[i].pass, events[i].passes) << "the image was not finished";
        EXPECT_LT(events[i].percent, 100.0);
    }
    EXPECT_EQ(events[3].kind, Kind::kCompleted);
    EXPECT_GE(events[3].frame, 3u + 30u) << "96x72 in 16-pixel tiles, one a frame";
    EXPECT_TRUE(summary->first_complete_seconds);
    EXPECT_GE(summary->refining_frames, events[3].frame - events[2].frame);
    EXPECT_EQ(summary->last_mode, RenderMode::kLightcuts);
    EXPECT_EQ(session.view().error_ratio, 0.01f);
    EXPECT_GT(glm::length(session.view().camera.eye - camera.eye), 0.5f);
    EXPECT_EQ(context->validation_message_count(), 0u);
    expect_same_radiance(dir / "refined.pfm", dir / "whole.pfm");
    std::filesystem::remove_all(dir);
}

TEST(EditorProgressive, ImportanceDrawnRepresentativesRefineToTheWholeFrame) {
    // The per-pixel draws are keyed by the pixel's place in the image, so an
    // image refined in tiles over many frames is the whole frame's; and the
    // choice reaches the renderer (the tree's representatives shade differently).
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    const std::filesystem::path dir = test::make_temp_dir("editor-progressive-importance");
    std::unique_ptr<EditorSession> owned = room_in_lightcuts(dir);
    EditorSession& session = *owned;
    const std::string script =
        "error-ratio 0.2\n"  // clusters on most cuts: draws matter
        "representatives importance\n"
        "wait-refined\n"
        "save-view " +
        (dir / "refined.pfm").string() + "\n" + "screenshot " + (dir / "whole.pfm").string() + "\n" +
        "representatives tree\n"  // wait-refined waits for the new image
        "wait-refined\n"
        "save-view " +
        (dir / "tree.pfm").string() + "\nquit\n";
    const ScriptedRun run = run_progressive_script(*context, session, script, 64, 48, false);
    ASSERT_TRUE(run.summary.ok()) << run.summary.error();
    EXPECT_EQ(run.script_state, ScriptState::kQuit) << run.script_error;
    EXPECT_EQ(session.view().representatives, Representatives::kTree);
    EXPECT_EQ(context->validation_message_count(), 0u);
    expect_same_radiance(dir / "refined.pfm", dir / "whole.pfm");
    const std::vector<float> importance = read_radiance(dir / "refined.pfm");
    const std::vector<float> by_tree = read_radiance(dir / "tree.pfm");
    ASSERT_EQ(importance.size(), by_tree.size());
    size_t differing = 0;
    for (size_t i = 0; i < importance.size(); ++i)
        differing += std::abs(importance[i] - by_tree[i]) > 1e-3f * (1.0f + std::abs(by_tree[i])) ? 1 : 0;
    EXPECT_GT(differing, importance.size() / 20) << "the importance draws did not reach the renderer";
    std::filesystem::remove_all(dir);
}

TEST(EditorProgressive, AutoExposureFromTheCoarsePassKeepsRefining) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    Scene scene = test::overexposed_lit_room(5);
    const RenderCamera camera = camera_from_scene(scene.cameras.at(0));
    EditorSession session(std::move(scene));
    ASSERT_TRUE(session.view_settings().set_camera(camera));
    const ScriptedRun run = run_progressive_script(*context, session, "wait-refined\nquit\n", 64, 48, true);
    const Result<EditorLoopSummary>& summary = run.summary;
    ASSERT_TRUE(summary.ok()) << summary.error();
    EXPECT_EQ(run.script_state, ScriptState::kQuit) << run.script_error;
    EXPECT_GT(session.view().exposure, 0.0f);
    EXPECT_LT(session.view().exposure, 0.01f) << "set from the coarse pass";
    // Only the start and the end: the new exposure tone-mapped the coarse image again.
    ASSERT_EQ(summary->refinement_events.size(), 2u);
    EXPECT_EQ(summary->refinement_events[1].kind, RefinementEvent::Kind::kCompleted);
    EXPECT_EQ(context->validation_message_count(), 0u);
}

TEST(EditorProgressive, XvfbViewHandlesInputWhileTheImageRefines) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed";
    std::unique_ptr<vk::Context> probe;
    LC_REQUIRE_VULKAN(probe);
    probe.reset();

    const std::filesystem::path dir = test::make_temp_dir("editor-progressive-xvfb");
    const Scene scene = test::lit_room(11);
    const std::filesystem::path scene_path = dir / "room.gltf";
    ASSERT_TRUE(write_scene_gltf(scene, scene_path).ok());
    const std::filesystem::path tree = test::write_tree_dump(scene, dir);
    const std::filesystem::path script_path = dir / "script.txt";
    {
        std::ofstream out(script_path);
        out << input_while_refining_script(camera_from_scene(scene.cameras.at(0)), dir);
    }
    // No --mode: with a tree the view opens in lightcuts mode; progressive is the
    // default. A fixed exposure: the automatic one would restart the image once more.
    const std::filesystem::path log = dir / "view.log";
    const std::string command = "xvfb-run -a " + (test::bin_dir() / "editor_client").string() + " view " +
                                scene_path.string() + " --tree " + tree.string() +
                                " --size 96x72 --exposure 1 --frame-budget-ms 0.001 --validation --script " +
                                script_path.string() + " > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    const std::string text = test::read_text(log);
    ASSERT_EQ(status, 0) << text;
    EXPECT_NE(text.find("last in lightcuts mode"), std::string::npos) << text;
    EXPECT_NE(text.find("0 validation messages"), std::string::npos) << text;

    // "refinement: frame F at S s restarted, pass P of N was X% done"
    const std::regex restarted(R"(refinement: frame (\d+) at [\d.]+ s restarted, pass (\d+) of (\d+) was ([\d.]+)% done)");
    std::vector<std::pair<uint32_t, double>> restarts;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), restarted); it != std::sregex_iterator(); ++it)
        restarts.emplace_back(uint32_t(std::stoul((*it)[1])), std::stod((*it)[4]));
    ASSERT_EQ(restarts.size(), 2u) << text;
    EXPECT_EQ(restarts[0].first, 2u) << "the camera moved in frame 2";
    EXPECT_EQ(restarts[1].first, 3u) << "the error ratio changed in frame 3";
    for (const auto& [frame, percent] : restarts) EXPECT_LT(percent, 100.0) << "frame " << frame;
    std::smatch completed;
    ASSERT_TRUE(std::regex_search(text, completed, std::regex(R"(refinement: frame (\d+) at [\d.]+ s completed)")))
        << text;
    EXPECT_GE(std::stoul(completed[1]), 3u + 30u);
    std::smatch rate;
    ASSERT_TRUE(std::regex_search(text, rate,
                                  std::regex(R"(progressive: (\d+) frames while refining .* first complete image in)")))
        << text;
    EXPECT_GT(std::stoul(rate[1]), 30u);
    expect_same_radiance(dir / "refined.pfm", dir / "whole.pfm");
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lc::client
