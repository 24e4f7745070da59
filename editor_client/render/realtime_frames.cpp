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
        sum.timing.render_ms += frame->timing.render_ms;
        sum.timing.gbuffer_ms += frame->timing.gbuffer_ms;
        sum.timing.lighting_ms += frame->timing.lighting_ms;
        sum.timing.output_ms += frame->timing.output_ms;
        sum.timing.wall_ms += frame->timing.wall_ms;
        last = std::move(frame).value();
    }
    const double n = double(frames);
    last.timing.render_ms = sum.timing.render_ms / n;
    last.timing.gbuffer_ms = sum.timing.gbuffer_ms / n;
    last.timing.lighting_ms = sum.timing.lighting_ms / n;
    last.timing.output_ms = sum.timing.output_ms / n;
    last.timing.wall_ms = sum.timing.wall_ms / n;
    return last;
}

}  // namespace lc::client
