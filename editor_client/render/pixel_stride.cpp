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

Result<std::vector<PixelRegion>> strided_tiles(uint32_t width, uint32_t height, uint32_t tile,
                                               uint32_t stride) {
    if (stride == 0 || tile == 0)
        return make_error("tile stride 0 or tile 0: both must be at least 1");
    const uint32_t block = stride * tile;
    if (width % block != 0 || height % block != 0)
        return make_error("a stride of " + std::to_string(stride) + " tiles of " +
                          std::to_string(tile) + " pixels does not divide the " +
                          std::to_string(width) + "x" + std::to_string(height) + " image");
    std::vector<PixelRegion> tiles;
    const uint32_t middle = (stride / 2) * tile;
    for (uint32_t y = 0; y < height; y += block)
        for (uint32_t x = 0; x < width; x += block)
            tiles.push_back({x + middle, y + middle, tile, tile});
    return tiles;
}

}  // namespace lc::client
