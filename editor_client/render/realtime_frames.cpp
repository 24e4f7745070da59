#include "editor_client/render/realtime_frames.h"

#include <string>

namespace lc::client {

Result<RenderStats> render_realtime_frames(Renderer& renderer, const RenderSettings& settings,
                                            uint32_t frames) {
    if (!mode_accumulates(settings.mode))
        return make_error("--frames accumulates the real-time modes (--mode realtime or restir)");
    if (frames < 1 || frames > kMaxRealtimeFrames)
        return make_error("--frames " + std::to_string(frames) + " is outside 1 .. " +
                          std::to_string(kMaxRealtimeFrames));
    RenderStats sum;
    RenderStats last;
    for (uint32_t f = 0; f < frames; ++f) {
        Result<RenderStats> frame = renderer.render(settings);
        if (!frame) return make_error(frame.error());
        sum.render_ms += frame->render_ms;
        sum.gbuffer_ms += frame->gbuffer_ms;
        sum.lighting_ms += frame->lighting_ms;
        sum.output_ms += frame->output_ms;
        sum.wall_ms += frame->wall_ms;
        last = std::move(frame).value();
    }
    const double n = double(frames);
    last.render_ms = sum.render_ms / n;
    last.gbuffer_ms = sum.gbuffer_ms / n;
    last.lighting_ms = sum.lighting_ms / n;
    last.output_ms = sum.output_ms / n;
    last.wall_ms = sum.wall_ms / n;
    return last;
}

}  // namespace lc::client
