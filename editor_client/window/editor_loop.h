#pragma once
// The frame loop of the interactive editor (`editor_client view`), in steps:
// input (the window's events, the panels, the camera: view_controls.h),
// update (the bake in flight, the `--script`, the renderer kept in step with
// the edited lights and the imported tree: renderer_sync.h), scheduling (a
// whole image, a reduced one while the camera moves, or a progressive image's
// tiles: frame_schedule.h), render, present (frame_presenter.h), then
// auto-exposure (view_auto_exposure.h) and the frame's statistics; screenshots
// go through the loop's EditorHost (editor_loop_host.h). Works with a GLFW
// window or a HeadlessWindow (frames rendered, never presented).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "editor_client/editor/adaptive_resolution.h"
#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/frame_schedule.h"
#include "editor_client/editor/overlay_text.h"
#include "editor_client/editor/progressive_refinement.h"
#include "editor_client/editor/script_runner.h"
#include "lightcuts/occlusion/shadow_ray.h"
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
    PrimaryChoice primary = PrimaryChoice::kAuto;  // how the renderer makes the G-buffer
    // Refine the view over frames, coarse to fine, in tiles within a GPU budget
    // per frame (progressive_refinement.h), so input and the panels are
    // handled every frame; otherwise each frame renders a whole image. The
    // coarse pass is AdaptiveResolution's divisor for a frame of that budget.
    bool progressive = false;
    ProgressiveOptions refinement;
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
    // Progressive view: every start, restart and completion, and the frames
    // drawn while an image was refining (the frame rate the UI keeps then).
    std::vector<RefinementEvent> refinement_events;
    std::optional<double> first_complete_seconds;  // since the loop started
    uint32_t refining_frames = 0;
    double refining_seconds = 0.0;
};

Result<EditorLoopSummary> run_editor_loop(Window& window, const vk::Context& context, EditorSession& session,
                                          const EditorLoopOptions& options);

}  // namespace lc::client
