#pragma once
// Every stride-th pixel of a frame, in x and y, rendered as a frame of its
// own: pixel (i, j) of the strided frame has the eye ray of pixel
// (stride * i, stride * j) of the full one, so each pixel's work is the same
// and the time scales by 1 / stride^2. A reference too long for the machine
// (131,072 lights at 256x256 on lavapipe) is measured this way, and the
// image it is compared with is sampled at the same pixels.
#include <cstdint>

#include "editor_client/render/render_settings.h"
#include "lightcuts/result.h"

namespace lc::client {

// The strided frame of `settings`: its sides divided by `stride` (which must
// divide them), each eye ray moved from the strided pixel's centre to the
// first full pixel's centre. A stride of 1 returns the settings as they are.
Result<RenderSettings> strided_settings(const RenderSettings& settings, uint32_t stride);

}  // namespace lc::client
