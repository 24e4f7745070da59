// The overlay's text: frame time, view controls, light counts, tree state.
#include <gtest/gtest.h>

#include "editor_client/editor/overlay_text.h"
#include "editor_client/scene/scene_generator.h"

namespace lc::client {
namespace {

bool has_line(const std::vector<std::string>& lines, const std::string& text) {
    for (const std::string& line : lines)
        if (line.find(text) != std::string::npos) return true;
    return false;
}

TEST(EditorOverlay, ShowsFrameViewAndLightCounts) {
    EditorSession session(make_room_scene());
    ASSERT_TRUE(session.edits().add_light(SceneLight{.position = {0, 1, 0}, .intensity = 2.0f}));
    ASSERT_TRUE(
        session.edits().add_light(SceneLight{.position = {1, 1, 0}, .intensity = 2.0f, .classic = true}));
    ASSERT_TRUE(session.view_settings().set_mode("lightcuts"));
    ASSERT_TRUE(session.view_settings().set_criterion("bound"));
    ASSERT_TRUE(session.view_settings().set_max_cut(300));

    FrameInfo frame{.frame_ms = 125.0,
                    .gpu_ms = 100.0,
                    .width = 320,
                    .height = 180,
                    .divisor = 2,
                    .avg_cut = 12.5,
                    .max_cut = 40u};
    const std::vector<std::string> lines = overlay_lines(session, frame);
    EXPECT_TRUE(has_line(lines, "frame 125.0 ms (8.0 fps), GPU 100.0 ms, 320x180 (moving"));
    EXPECT_TRUE(has_line(lines, "mode lightcuts, criterion bound, error 0.02, max cut 300"));
    EXPECT_TRUE(has_line(lines, "cut size: mean 12.5, max 40"));
    EXPECT_TRUE(has_line(lines, "lights 2 (1 in the tree, 1 classic)"));
    EXPECT_TRUE(has_line(lines, "tree: none"));
    EXPECT_FALSE(has_line(lines, "baking"));
    EXPECT_FALSE(has_line(lines, "last bake"));

    frame.avg_cut.reset();
    frame.divisor = 1;
    const std::vector<std::string> still = overlay_lines(session, frame);
    EXPECT_FALSE(has_line(still, "cut size"));
    EXPECT_FALSE(has_line(still, "moving"));
    EXPECT_FALSE(has_line(still, "refin"));
}

TEST(EditorOverlay, ShowsHowFarTheProgressiveImageHasRefined) {
    EditorSession session(make_room_scene());
    FrameInfo frame{.frame_ms = 40.0, .gpu_ms = 28.0, .width = 120, .height = 75, .divisor = 8};
    frame.refinement = RefinementProgress{.pass = 0, .passes = 2, .percent = 37.5, .divisor = 8};
    std::vector<std::string> lines = overlay_lines(session, frame);
    EXPECT_TRUE(has_line(lines, "120x75 (coarse pass)"));
    EXPECT_TRUE(has_line(lines, "refining: pass 1 of 2 (1/8 size), 38% of its tiles"));

    frame.divisor = 1;
    frame.refinement = RefinementProgress{.pass = 1, .passes = 2, .percent = 5.0, .divisor = 1};
    lines = overlay_lines(session, frame);
    EXPECT_TRUE(has_line(lines, "refining: pass 2 of 2 (full size), 5% of its tiles"));

    frame.refinement = RefinementProgress{.pass = 2, .passes = 2};
    lines = overlay_lines(session, frame);
    EXPECT_TRUE(has_line(lines, "refined: 2 of 2 passes"));
    EXPECT_FALSE(has_line(lines, "refining"));
}

}  // namespace
}  // namespace lc::client
