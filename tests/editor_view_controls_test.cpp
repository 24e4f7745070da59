// The editor loop's input step (window/view_controls.h) without a window: the
// mouse and keys a window reports move the session's camera and switch its
// mode, and a camera a script set is where the next orbit starts from.
#include "editor_client/window/view_controls.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "editor_client/scene/scene_generator.h"

namespace lc::client {
namespace {

RenderCamera start_camera() {
    RenderCamera camera;
    camera.eye = {0.0f, 1.5f, 4.0f};
    camera.target = {0.0f, 1.0f, 0.0f};
    camera.yfov = 0.9f;
    return camera;
}

class EditorViewControls : public ::testing::Test {
protected:
    void SetUp() override { ASSERT_TRUE(session_.view_settings().set_camera(start_camera())); }

    EditorSession session_{make_room_scene()};
};

TEST_F(EditorViewControls, NoInputLeavesTheViewAlone) {
    ViewControls controls(session_.view().camera);
    const ViewState before = session_.view();
    EXPECT_FALSE(controls.apply(WindowInput{}, session_, 16.0));
    EXPECT_EQ(session_.view().camera, before.camera);
    EXPECT_EQ(session_.view().mode, before.mode);
}

TEST_F(EditorViewControls, DragsAndTheWheelMoveTheCameraKeepingItsUp) {
    ViewControls controls(session_.view().camera);
    WindowInput orbit;
    orbit.orbit_drag = {40.0f, 0.0f};
    EXPECT_TRUE(controls.apply(orbit, session_, 16.0));
    const RenderCamera orbited = session_.view().camera;
    EXPECT_NE(orbited.eye, start_camera().eye);
    EXPECT_NEAR(glm::distance(orbited.eye, orbited.target),
                glm::distance(start_camera().eye, start_camera().target), 1e-4f)
        << "an orbit keeps the distance";
    EXPECT_EQ(orbited.up, start_camera().up);

    WindowInput dolly;
    dolly.scroll = 1.0f;
    EXPECT_TRUE(controls.apply(dolly, session_, 16.0));
    EXPECT_LT(glm::distance(session_.view().camera.eye, session_.view().camera.target),
              glm::distance(orbited.eye, orbited.target))
        << "the wheel away from the user moves in";
}

TEST_F(EditorViewControls, FlyingCoversMoreGroundInASlowerFrameUpToTheCap) {
    const auto flown = [&](double frame_ms) {
        EXPECT_TRUE(session_.view_settings().set_camera(start_camera()));
        ViewControls controls(session_.view().camera);
        WindowInput fly;
        fly.fly = {0.0f, 0.0f, 1.0f};
        EXPECT_TRUE(controls.apply(fly, session_, frame_ms));
        return glm::distance(session_.view().camera.eye, start_camera().eye);
    };
    const float at_60hz = flown(1000.0 / 60.0);
    EXPECT_GT(at_60hz, 0.0f);
    EXPECT_FLOAT_EQ(flown(1.0), at_60hz) << "frames faster than 60 Hz fly as far as one at 60 Hz";
    EXPECT_NEAR(flown(100.0), at_60hz * 6.0f, at_60hz * 1e-3f);
    EXPECT_FLOAT_EQ(flown(1000.0), flown(250.0)) << "one slow frame is not a leap";
}

TEST_F(EditorViewControls, ACameraSetElsewhereIsWhereTheNextOrbitStarts) {
    ViewControls controls(session_.view().camera);
    RenderCamera scripted = start_camera();
    scripted.eye = {3.0f, 2.0f, 0.0f};
    ASSERT_TRUE(session_.view_settings().set_camera(scripted));
    EXPECT_FALSE(controls.apply(WindowInput{}, session_, 16.0));
    EXPECT_EQ(session_.view().camera, scripted) << "no input: the scripted camera stays";

    WindowInput orbit;
    orbit.orbit_drag = {1.0f, 0.0f};
    ASSERT_TRUE(controls.apply(orbit, session_, 16.0));
    EXPECT_LT(glm::distance(session_.view().camera.eye, scripted.eye), 0.2f)
        << "a small drag from the scripted camera, not from the start";
}

TEST_F(EditorViewControls, NumberKeysChooseTheModeAndOthersAreIgnored) {
    ViewControls controls(session_.view().camera);
    WindowInput key;
    key.mode_key = 3;
    EXPECT_FALSE(controls.apply(key, session_, 16.0)) << "a mode key is not a camera move";
    EXPECT_EQ(session_.view().mode, RenderMode::kCuts);
    key.mode_key = kRenderModeCount + 1;
    controls.apply(key, session_, 16.0);
    EXPECT_EQ(session_.view().mode, RenderMode::kCuts);
    key.mode_key = 0;
    controls.apply(key, session_, 16.0);
    EXPECT_EQ(session_.view().mode, RenderMode::kCuts);
}

}  // namespace
}  // namespace lc::client
