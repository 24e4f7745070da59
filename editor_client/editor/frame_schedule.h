#pragma once
// The editor's scheduling step, without a window or a GPU: from the view's
// settings at full size and what happened since the last frame, what the next
// frame renders (a whole image, a reduced one while the camera moves, or a
// progressive image's next tiles), and, once the frame ran, what its timings
// teach the schedule. Keeps the progressive view's start, restart and
// completion events.
#include <cstdint>
#include <optional>
#include <vector>

#include "editor_client/editor/adaptive_resolution.h"
#include "editor_client/editor/overlay_text.h"
#include "editor_client/editor/progressive_refinement.h"
#include "editor_client/render/settings/render_settings.h"

namespace lc::client {

// What the progressive view did, frame by frame.
struct RefinementEvent {
    enum class Kind { kStarted, kRestarted, kCompleted };
    Kind kind = Kind::kStarted;
    uint32_t frame = 0;    // 0-based frame of the loop
    double seconds = 0.0;  // since the loop started
    double percent = 0.0;  // restarted: of the pass that was refining
    uint32_t pass = 0;     // restarted: the pass that was refining (0-based)
    uint32_t passes = 0;
};

const char* refinement_event_name(RefinementEvent::Kind kind);

struct FrameScheduleOptions {
    uint32_t width = 800;  // the view's full size
    uint32_t height = 600;
    bool adaptive_resolution = true;  // reduced size while the camera moves (whole images only)
    AdaptiveResolutionOptions adaptive;
    // Refine the view in tiles (progressive_refinement.h); the coarse pass is
    // AdaptiveResolution's divisor for a frame of `refinement.frame_budget_ms`.
    bool progressive = false;
    ProgressiveOptions refinement;
    uint32_t tile_alignment = 8;  // the renderer's compute workgroup size
};

// One frame's work, as the schedule decided it.
struct FramePlan {
    RenderSettings settings;  // the size is the pass's or the reduced one
    uint32_t divisor = 1;     // of the full width and height
    bool realtime = false;    // whole frames at full size: its history refines the view
    bool tiled = false;       // a progressive image's tiles (none once it is complete)
    std::optional<TileBatch> batch;
};

// What happened since the last frame that decides the next one.
struct FrameInputs {
    RenderSettings settings;        // the view's, at full size
    uint64_t renderer_updates = 0;  // RendererSync::updates(): the lights or tree changed
    bool image_lost = false;        // a screenshot overwrote the unfinished image
    bool moved = false;             // the camera moved this frame
    uint32_t frame = 0;             // 0-based frame of the loop
    double now_ms = 0.0;            // since the loop started
};

class FrameSchedule {
public:
    explicit FrameSchedule(const FrameScheduleOptions& options);

    // Whether a frame of `settings` takes a progressive image's tiles.
    bool tiled(const RenderSettings& settings) const;
    FramePlan plan(const FrameInputs& inputs);
    // After the frame's GPU work: a progressive frame's own time (lighting and
    // tone mapping of its tiles) teaches the refinement and the coarse pass's size.
    void report_gpu(const FramePlan& plan, double tiles_ms);
    // After the frame, with its wall time in `frame.frame_ms`: where a progressive
    // image stands (`frame.refinement`), refining frames counted, a completion
    // recorded; a whole frame's time teaches the adaptive resolution.
    void finish_frame(const FramePlan& plan, FrameInfo& frame, uint32_t frame_index, double now_ms);
    // The first whole image (coarse or not) was drawn by this frame.
    bool whole_image(const FramePlan& plan) const;
    // The exposure changed while the image refines: the lit tiles are tone-mapped
    // again, and the image being refined is the same one.
    void set_refined_exposure(float exposure) { refined_.exposure = exposure; }

    bool progressive() const { return refinement_.has_value(); }
    // A progressive image is refining (started and not complete).
    bool refining() const { return refinement_ && !refinement_->complete(); }
    // A complete progressive image of `settings` with the renderer's lights and
    // tree as `updates` counted them.
    bool refined_for(const RenderSettings& settings, uint64_t updates) const;

    const std::vector<RefinementEvent>& events() const { return events_; }
    std::optional<double> first_complete_seconds() const { return first_complete_seconds_; }
    uint32_t refining_frames() const { return refining_frames_; }
    double refining_seconds() const { return refining_seconds_; }

private:
    void restart_if_changed(const FrameInputs& inputs);

    FrameScheduleOptions options_;
    std::optional<ProgressiveRefinement> refinement_;
    AdaptiveResolution adaptive_;
    // What the progressive image is refined for: the settings and the
    // renderer's lights and tree (RendererSync::updates) it started with.
    RenderSettings refined_;
    uint64_t refined_updates_ = 0;
    std::vector<RefinementEvent> events_;
    std::optional<double> first_complete_seconds_;
    uint32_t refining_frames_ = 0;
    double refining_seconds_ = 0.0;
};

}  // namespace lc::client
