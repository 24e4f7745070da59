#include "editor_client/editor/frame_schedule.h"

namespace lc::client {

const char* refinement_event_name(RefinementEvent::Kind kind) {
    switch (kind) {
        case RefinementEvent::Kind::kStarted:
            return "started";
        case RefinementEvent::Kind::kRestarted:
            return "restarted";
        case RefinementEvent::Kind::kCompleted:
            return "completed";
    }
    return "started";
}

namespace {

// The coarse pass of a progressive view is the size whose whole image fits one frame's budget.
AdaptiveResolutionOptions adaptive_options_for(const FrameScheduleOptions& options) {
    AdaptiveResolutionOptions adaptive = options.adaptive;
    if (options.progressive) adaptive.target_frame_ms = options.refinement.frame_budget_ms;
    return adaptive;
}

}  // namespace

FrameSchedule::FrameSchedule(const FrameScheduleOptions& options)
    : options_(options), adaptive_(adaptive_options_for(options)) {
    if (options.progressive)
        refinement_.emplace(options.width, options.height, options.tile_alignment, options.refinement);
}

bool FrameSchedule::tiled(const RenderSettings& settings) const {
    // The real-time mode shows whole frames at the full size: its history
    // refines the view, not tiles or a coarser size.
    return refinement_ && !mode_accumulates(settings.mode);
}

FramePlan FrameSchedule::plan(const FrameInputs& inputs) {
    FramePlan plan;
    plan.settings = inputs.settings;
    plan.realtime = mode_accumulates(inputs.settings.mode);
    plan.tiled = tiled(inputs.settings);
    if (plan.tiled) {
        restart_if_changed(inputs);
        plan.batch = refinement_->next_batch();
        if (plan.batch) {
            plan.divisor = plan.batch->divisor;
            plan.settings.width = plan.batch->width;
            plan.settings.height = plan.batch->height;
        }
    } else if (!plan.realtime) {
        plan.divisor = options_.adaptive_resolution ? adaptive_.next_divisor(inputs.moved, inputs.now_ms) : 1;
        plan.settings.width = reduced_size(options_.width, plan.divisor);
        plan.settings.height = reduced_size(options_.height, plan.divisor);
    }
    return plan;
}

void FrameSchedule::restart_if_changed(const FrameInputs& inputs) {
    // The same image: every setting equal (an exposure change tone-maps anew, so it refines anew).
    if (!events_.empty() && !inputs.image_lost && inputs.settings == refined_ &&
        inputs.renderer_updates == refined_updates_)
        return;
    RefinementEvent event;
    event.kind = events_.empty() ? RefinementEvent::Kind::kStarted : RefinementEvent::Kind::kRestarted;
    event.frame = inputs.frame;
    event.seconds = inputs.now_ms / 1000.0;
    event.percent = refinement_->percent();
    event.pass = refinement_->pass();
    event.passes = refinement_->passes();
    events_.push_back(event);
    refinement_->restart(adaptive_.divisor_meeting_target());
    refined_ = inputs.settings;
    refined_updates_ = inputs.renderer_updates;
}

void FrameSchedule::report_gpu(const FramePlan& plan, double tiles_ms) {
    if (!plan.batch) return;
    refinement_->report(*plan.batch, tiles_ms);
    const double pass_pixels = double(plan.batch->width) * double(plan.batch->height);
    adaptive_.report_frame(plan.divisor, tiles_ms * pass_pixels / double(plan.batch->pixels()));
}

void FrameSchedule::finish_frame(const FramePlan& plan, FrameInfo& frame, uint32_t frame_index,
                                 double now_ms) {
    if (!plan.tiled) {
        adaptive_.report_frame(plan.divisor, frame.frame_ms);
        return;
    }
    RefinementProgress progress;
    progress.pass = refinement_->pass();
    progress.passes = refinement_->passes();
    progress.percent = refinement_->percent();
    progress.divisor = plan.divisor;
    frame.refinement = progress;
    if (!plan.batch) return;
    refining_frames_ += 1;
    refining_seconds_ += frame.frame_ms / 1000.0;
    if (!refinement_->complete()) return;
    RefinementEvent event;
    event.kind = RefinementEvent::Kind::kCompleted;
    event.frame = frame_index;
    event.seconds = now_ms / 1000.0;
    event.percent = 100.0;
    event.pass = event.passes = refinement_->passes();
    events_.push_back(event);
    if (!first_complete_seconds_) first_complete_seconds_ = event.seconds;
}

bool FrameSchedule::whole_image(const FramePlan& plan) const {
    if (plan.tiled) return plan.batch && refinement_->pass() > plan.batch->pass;
    return plan.divisor == 1;
}

bool FrameSchedule::refined_for(const RenderSettings& settings, uint64_t updates) const {
    return refinement_ && refinement_->complete() && refined_updates_ == updates && settings == refined_;
}

}  // namespace lc::client
