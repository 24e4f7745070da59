#pragma once
// The real-time sweep's moving camera: a scripted orbit that starts at the
// scene's camera, deterministic, so every variant sees the same frames.
#include <cstdint>
#include <vector>

#include "editor_client/render/settings/render_settings.h"

namespace lc::client {

// The yaw of the whole path about the camera's up axis through its target:
// small enough to stay inside a room, large enough that every frame moves.
inline constexpr float kSweepOrbitDegrees = 24.0f;

// `frames` cameras: the first is `start`, each next one turned by
// total_degrees / (frames - 1) about `start.up` through `start.target`.
std::vector<RenderCamera> orbit_path(const RenderCamera& start, uint32_t frames,
                                     float total_degrees = kSweepOrbitDegrees);

}  // namespace lc::client
