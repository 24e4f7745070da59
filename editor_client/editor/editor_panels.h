#pragma once
// The editor's Dear ImGui panels: view controls (mode, criterion, error ratio,
// max cut, exposure), the light list with select and delete, the add-light
// form (typed position or a click on a surface), procedural lights, undo,
// save, Build lighting with progress and cancel, errors, and the overlay.
// Pure ImGui calls against an EditorSession: the window owns the backends,
// and the panels can be drawn in a test with no display at all.
#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/overlay_text.h"
#include "editor_client/editor/script_runner.h"
#include "editor_client/editor/server_status_poller.h"

namespace lc::client {

// What the panels keep between frames: the forms' contents and the last message.
struct PanelState {
    int light_type = 0;  // point, spot, directional
    std::array<float, 3> position{0.0f, 1.0f, 0.0f};
    std::array<float, 3> direction{0.0f, -1.0f, 0.0f};
    std::array<float, 3> color{1.0f, 0.9f, 0.8f};
    float intensity = kDefaultPointIntensity;
    float range = 0.0f;
    bool classic = false;
    bool place_by_click = false;  // the next click in the view sets `position`

    int procedural_count = 64;
    int procedural_layout = 0;  // random, grid
    int procedural_seed = 1;

    std::array<char, 512> save_path{};
    // Asks the bake server for its status off the render thread; made when the
    // session has a server (a spawned one: after its first bake).
    std::shared_ptr<ServerStatusPoller> server_status;
    std::string message;  // the last action's outcome
    bool message_is_error = false;
};

// How often the server panel asks for the status, and how long one query may take.
inline constexpr std::chrono::milliseconds kServerStatusInterval{3000};
inline constexpr double kServerStatusTimeoutSeconds = 2.0;

// A click in the view (not on a panel), in window pixels.
struct ViewClick {
    double x = 0.0;
    double y = 0.0;
    uint32_t window_width = 1;
    uint32_t window_height = 1;
};

// Draws every panel for this ImGui frame and applies what the user did to the
// session (through the same functions `--script` uses). `click` is applied
// first: it places the add-light form's position or selects a light.
void draw_editor_panels(EditorSession& session, EditorHost& host, PanelState& state, const FrameInfo& frame,
                        const std::optional<ViewClick>& click);

// The part of draw_editor_panels that handles a click (tested on its own).
// With place_by_click: the surface under the cursor (lifted off it) becomes
// the form's position; otherwise the light nearest the ray is selected.
// Returns false when the click hit nothing it could use.
bool apply_view_click(EditorSession& session, PanelState& state, const ViewClick& click);

}  // namespace lc::client
