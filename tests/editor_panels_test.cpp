// The editor's ImGui panels drawn without a display (ImGui's own context, no
// backend), and clicks in the view: placing a light on a surface, selecting a
// light.
#include <gtest/gtest.h>
#include <imgui.h>

#include "editor_client/editor/editor_panels.h"
#include "editor_client/editor/editor_session.h"
#include "editor_client/scene/scene_generator.h"

namespace lc::client {
namespace {

class NullHost final : public EditorHost {
public:
    Status screenshot(const std::filesystem::path&) override { return Ok{}; }
    void request_quit() override {}
};

// An ImGui context with a built font atlas, as the Vulkan backend would have.
class ImGuiFixture : public ::testing::Test {
protected:
    void SetUp() override {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(1280, 720);
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int width = 0, height = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    }
    void TearDown() override { ImGui::DestroyContext(); }
};

RenderCamera looking_at(const glm::vec3& eye, const glm::vec3& target) {
    RenderCamera camera;
    camera.eye = eye;
    camera.target = target;
    camera.yfov = 0.9f;
    return camera;
}

TEST_F(ImGuiFixture, PanelsDrawEveryControlAndTheOverlay) {
    EditorSession session(make_room_scene());
    ASSERT_TRUE(session.edits().add_light(SceneLight{}).ok());
    NullHost host;
    PanelState state;
    FrameInfo frame;
    frame.frame_ms = 20.0;
    frame.width = 640;
    frame.height = 360;
    for (int i = 0; i < 3; ++i) {
        ImGui::NewFrame();
        draw_editor_panels(session, host, state, frame, std::nullopt);
        ImGui::Render();
    }
    const ImDrawData* draw = ImGui::GetDrawData();
    ASSERT_NE(draw, nullptr);
    EXPECT_GE(draw->CmdListsCount, 2);  // the panel window and the overlay
    EXPECT_GT(draw->TotalVtxCount, 1000);
    EXPECT_STREQ(state.save_path.data(), "edited.gltf");
    // Drawing alone changes nothing in the session.
    EXPECT_EQ(session.scene().lights.size(), 1u);
    EXPECT_EQ(session.edits().undo_stack().undo_depth(), 1u);
}

TEST_F(ImGuiFixture, ClickPlacesTheNewLightAboveTheSurfaceUnderTheCursor) {
    EditorSession session(make_room_scene());
    // Looking straight down at the floor (y = 0) from above its centre.
    ASSERT_TRUE(session.view_settings().set_camera(looking_at({0.3f, 2.5f, 0.2f}, {0.3f, 0.0f, 0.21f})));
    PanelState state;
    state.place_by_click = true;
    ViewClick click{320.0 - 0.5, 180.0 - 0.5, 640, 360};  // the centre pixel
    ASSERT_TRUE(apply_view_click(session, state, click)) << state.message;
    EXPECT_FALSE(state.message_is_error) << state.message;
    EXPECT_FALSE(state.place_by_click);  // one click, one placement
    EXPECT_NEAR(state.position[0], 0.3f, 0.02f);
    EXPECT_NEAR(state.position[1], 0.1f, 1e-3f);  // lifted off the floor along its normal
    EXPECT_NEAR(state.position[2], 0.21f, 0.02f);
}

TEST_F(ImGuiFixture, ClickWithoutPlacingSelectsTheLightUnderTheCursor) {
    EditorSession session(make_room_scene());
    SceneLight a;
    a.position = {-2.0f, 1.5f, 0.0f};
    SceneLight b;
    b.position = {2.0f, 1.5f, 0.0f};
    ASSERT_TRUE(session.edits().add_light(a).ok());
    ASSERT_TRUE(session.edits().add_light(b).ok());
    ASSERT_TRUE(session.edits().select(std::nullopt));
    ASSERT_TRUE(session.view_settings().set_camera(looking_at({0.0f, 1.5f, 4.0f}, a.position)));
    PanelState state;
    ASSERT_TRUE(apply_view_click(session, state, ViewClick{319.5, 179.5, 640, 360}));
    EXPECT_EQ(session.edits().selection(), std::optional<size_t>(0));
    // A click at the far corner points away from both lights: nothing selected.
    EXPECT_FALSE(apply_view_click(session, state, ViewClick{0.5, 0.5, 640, 360}));
    EXPECT_EQ(session.edits().selection(), std::optional<size_t>(0));
}

}  // namespace
}  // namespace lc::client
