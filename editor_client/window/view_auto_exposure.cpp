#include "editor_client/window/view_auto_exposure.h"

#include <span>
#include <vector>

#include "editor_client/render/analysis/error_stats.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

Status ViewAutoExposure::after_frame(FramePlan& plan, FrameSchedule& schedule, Renderer& renderer,
                                     EditorSession& session, const vk::Context& context,
                                     std::optional<ProgressiveCanvas>& canvas) {
    if (!pending_ || !schedule.whole_image(plan) || !mode_is_shaded(plan.settings.mode)) return Ok{};
    pending_ = false;
    // A script or the panel may have set one already: keep it.
    if (session.view().exposure != initial_) return Ok{};
    Result<std::vector<float>> hdr = renderer.read_hdr();
    if (!hdr) return make_error(hdr.error());
    LC_RETURN_IF_ERROR(session.view_settings().set_exposure(auto_exposure(*hdr)));
    if (!plan.tiled) return Ok{};
    return tone_map_again(plan, schedule, renderer, session, context, *canvas);
}

Status ViewAutoExposure::tone_map_again(FramePlan& plan, FrameSchedule& schedule, Renderer& renderer,
                                        const EditorSession& session, const vk::Context& context,
                                        ProgressiveCanvas& canvas) {
    schedule.set_refined_exposure(session.view().exposure);
    plan.settings.exposure = session.view().exposure;
    const PixelRegion whole{0, 0, plan.settings.width, plan.settings.height};
    Status toned = Ok{};
    LC_RETURN_IF_ERROR(context.command_pool().run_one_time(context.device(), [&](VkCommandBuffer c) {
        toned = renderer.record_output(c, plan.settings, std::span(&whole, 1));
        if (toned) canvas.record_tiles(c, renderer.display_image(), std::span(&whole, 1), plan.divisor);
    }));
    return toned;
}

}  // namespace lc::client
