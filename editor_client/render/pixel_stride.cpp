#include "editor_client/render/pixel_stride.h"

#include <string>

namespace lc::client {

Result<RenderSettings> strided_settings(const RenderSettings& settings, uint32_t stride) {
    if (stride == 0) return make_error("pixel stride 0: it must be at least 1");
    if (stride == 1) return settings;
    if (settings.width % stride != 0 || settings.height % stride != 0)
        return make_error("pixel stride " + std::to_string(stride) + " does not divide the " +
                          std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                          " image");
    if (settings.corner_grid || settings.pixel_offset.x != 0.0f || settings.pixel_offset.y != 0.0f)
        return make_error("a strided frame places its eye rays itself (no corner grid or offset)");
    RenderSettings strided = settings;
    strided.width = settings.width / stride;
    strided.height = settings.height / stride;
    // A strided pixel spans `stride` full pixels; the full pixel it stands for
    // is its first, whose centre lies (stride - 1) / 2 full pixels before the
    // strided pixel's centre.
    const float offset = -float(stride - 1) / float(2 * stride);
    strided.pixel_offset = {offset, offset};
    return strided;
}

}  // namespace lc::client
