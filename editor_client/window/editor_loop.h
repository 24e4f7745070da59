#pragma once
// The frame loop of the interactive editor (`editor_client view`): each frame
// polls input and the bake in flight, steps the `--script`, keeps the renderer
// in step with the edited lights and the imported tree, renders the session's
// view (at reduced resolution while the camera moves) and presents it. Works
// with a GLFW window or a HeadlessWindow (frames rendered, never presented).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "editor_client/editor/adaptive_resolution.h"
#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/overlay_text.h"
#include "editor_client/editor/script_runner.h"
#include "lightcuts/shadow_ray.h"
#include "editor_client/vk/context.h"
#include "editor_client/window/window.h"
#include "lightcuts/result.h"

namespace lc::client {

struct EditorLoopOptions {
    uint32_t width = 800;  // full render size (the window may differ: the blit scales)
    uint32_t height = 600;
    uint32_t frames = 0;               // stop after this many frames; 0: until closed or `quit`
    std::filesystem::path screenshot;  // when set, a full-size frame is saved at the end
    ScriptRunner* script = nullptr;    // stepped once per frame (may be null)
    bool adaptive_resolution = true;
    // Set the exposure once from the first full-size reference or lightcuts
    // frame (auto_exposure in error_stats.h), unless it was changed by then.
    bool auto_exposure = false;
    // Added to the user's orbit drag every frame, in pixels: a camera that
    // keeps moving, for measuring the frame rate while it does (0: off).
    float orbit_drag_per_frame = 0.0f;
    // The window as shown, panels included, saved at the end (needs panels).
    std::filesystem::path window_screenshot;
    // Dear ImGui panels over the view (needs a GlfwWindow: ignored headless).
    bool panels = false;
    AdaptiveResolutionOptions adaptive;
    ShadowMode shadows = ShadowMode::kAuto;  // the renderer's (scene analysis by default)
};

struct EditorLoopSummary {
    uint32_t frames = 0;
    double seconds = 0.0;
    // Frames and wall time after the script finished (all frames without one):
    // what the editor's steady frame rate is measured on.
    uint32_t steady_frames = 0;
    double steady_seconds = 0.0;
    FrameInfo last_frame;
    RenderMode last_mode = RenderMode::kReference;  // what the last frame rendered
    ScriptState script_state = ScriptState::kFinished;
    uint32_t screenshots = 0;
};

Result<EditorLoopSummary> run_editor_loop(Window& window, const vk::Context& context, EditorSession& session,
                                          const EditorLoopOptions& options);

}  // namespace lc::client
