#pragma once
// The editor's auto-exposure step (`view` without --exposure): the first whole
// shaded image, coarse or not, sets the view's exposure (auto_exposure in
// error_stats.h), unless a script or a panel set one by then. A progressive
// image goes on refining: the tiles it lit so far are tone-mapped again.
#include <optional>

#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/frame_schedule.h"
#include "editor_client/render/renderer.h"
#include "editor_client/vk/context.h"
#include "editor_client/window/progressive_canvas.h"
#include "lightcuts/result.h"

namespace lc::client {

class ViewAutoExposure {
public:
    ViewAutoExposure(bool enabled, float initial_exposure) : pending_(enabled), initial_(initial_exposure) {}

    // After a frame (the GPU idle) that rendered `plan`. May change the plan's
    // exposure to the one the image was tone-mapped again with.
    Status after_frame(FramePlan& plan, FrameSchedule& schedule, Renderer& renderer, EditorSession& session,
                       const vk::Context& context, std::optional<ProgressiveCanvas>& canvas);

private:
    Status tone_map_again(FramePlan& plan, FrameSchedule& schedule, Renderer& renderer,
                          const EditorSession& session, const vk::Context& context,
                          ProgressiveCanvas& canvas);

    bool pending_;
    float initial_;  // the view's exposure when the loop started
};

}  // namespace lc::client
