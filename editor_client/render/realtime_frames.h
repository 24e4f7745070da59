#pragma once
// The real-time mode rendered headless over several frames of a still view
// (render --mode realtime --frames N): the image is the mean the history
// holds after the last frame; the statistics are the last frame's counters
// with each timing averaged over the frames.
#include <cstdint>

#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/output/render_stats.h"
#include "editor_client/render/renderer.h"
#include "lightcuts/result.h"

namespace lc::client {

inline constexpr uint32_t kMaxRealtimeFrames = 1u << 16;

Result<RenderStats> render_realtime_frames(Renderer& renderer, const RenderSettings& settings,
                                            uint32_t frames);

}  // namespace lc::client
