#pragma once
// The editor's input step: the window's mouse and keys since the last frame
// applied to the session's view (orbit, pan, look, dolly, fly, the mode keys).
// A camera a script or a panel set is where the next orbit starts from.
#include <glm/vec2.hpp>

#include "editor_client/editor/editor_session.h"
#include "editor_client/window/orbit_camera.h"
#include "editor_client/window/window.h"

namespace lc::client {

class ViewControls {
public:
    explicit ViewControls(const RenderCamera& start) : orbit_(start), orbit_camera_(start) {}

    // Returns whether the input moved the camera (a reduced or restarted image
    // follows). `last_frame_ms` scales flying, so it keeps its speed at any frame rate.
    bool apply(const WindowInput& input, EditorSession& session, double last_frame_ms);

private:
    OrbitCamera orbit_;
    RenderCamera orbit_camera_;  // the camera orbit_ was made from or last moved to
};

}  // namespace lc::client
