#include "editor_client/window/view_controls.h"

#include <algorithm>

namespace lc::client {

bool ViewControls::apply(const WindowInput& input, EditorSession& session, double last_frame_ms) {
    // A script or a panel may have moved the camera: orbit from there.
    if (session.view().camera != orbit_camera_) {
        orbit_ = OrbitCamera(session.view().camera);
        orbit_camera_ = session.view().camera;
    }
    const bool moved = input.orbit_drag != glm::vec2(0.0f) || input.pan_drag != glm::vec2(0.0f) ||
                       input.look_drag != glm::vec2(0.0f) || input.fly != glm::vec3(0.0f) ||
                       input.scroll != 0.0f;
    if (moved) {
        orbit_.orbit(input.orbit_drag);
        orbit_.pan(input.pan_drag);
        orbit_.look(input.look_drag);
        orbit_.dolly(input.scroll);
        // Fly by the last frame's time (capped, so one slow frame is not a leap).
        const double frame_s = std::min(last_frame_ms, 250.0) / 1000.0;
        orbit_.fly(input.fly, orbit_.fly_speed() * float(std::max(frame_s, 1.0 / 60.0)));
        RenderCamera next = orbit_.camera();
        next.up = session.view().camera.up;
        if (session.view_settings().set_camera(next)) orbit_camera_ = session.view().camera;
    }
    if (input.mode_key && *input.mode_key >= 1 && *input.mode_key <= kRenderModeCount)
        session.view_settings().set_mode(static_cast<RenderMode>(*input.mode_key - 1));
    return moved;
}

}  // namespace lc::client
