#pragma once
// Every stride-th pixel of a frame, in x and y, rendered as a frame of its
// own: pixel (i, j) of the strided frame has the eye ray of pixel
// (stride * i, stride * j) of the full one, so each pixel's work is the same
// and the time scales by 1 / stride^2. A reference too long for the machine
// (131,072 lights at 256x256 on lavapipe) is measured this way, and the
// image it is compared with is sampled at the same pixels.
//
// A strided pixel's neighbours in a subgroup lie `stride` pixels apart, so
// their shadow rays are less coherent than in the full frame and the scaled
// time overstates it (1.31x at stride 4 measured). Tiles keep that coherence:
// every stride-th tile of the workgroup's size in x and y, each rendered at
// full resolution over the full frame's G-buffer (strided_tiles), and
// dispatched as one grid of workgroups (workgroup_lattice.h): one dispatch a
// tile ran on one of lavapipe's threads and overstated the time 1.9x on an
// idle 2-core machine.
#include <cstdint>
#include <span>
#include <vector>

#include "editor_client/render/gpu/pixel_region.h"
#include "editor_client/render/settings/render_settings.h"
#include "lightcuts/result.h"

namespace lc::client {

// The strided frame of `settings`: its sides divided by `stride` (which must
// divide them), each eye ray moved from the strided pixel's centre to the
// first full pixel's centre. A stride of 1 returns the settings as they are.
Result<RenderSettings> strided_settings(const RenderSettings& settings, uint32_t stride);

// The tiles of `tile` x `tile` pixels a frame strided over tiles renders: of
// every stride x stride block of tiles the middle one (away from the image's
// border, like the rest of the frame), row by row. stride * tile must divide
// both sides.
Result<std::vector<PixelRegion>> strided_tiles(uint32_t width, uint32_t height, uint32_t tile,
                                               uint32_t stride);

// The pixels of `tiles` (as strided_tiles gives them, over an image `width`
// pixels wide with `channels` values a pixel) side by side in one image of
// (width / stride) x (height / stride) pixels, each tile at its place in the
// grid of tiles.
template <typename T>
std::vector<T> gather_tiles(std::span<const T> image, uint32_t width, uint32_t channels,
                            std::span<const PixelRegion> tiles, uint32_t stride) {
    const uint32_t tile = tiles.empty() ? 1 : tiles.front().width;
    const uint32_t out_width = width / stride;
    const uint32_t tiles_x = out_width / tile;
    std::vector<T> out(size_t(tiles.size()) * tile * tile * channels);
    for (size_t t = 0; t < tiles.size(); ++t) {
        const uint32_t ox = uint32_t(t % tiles_x) * tile, oy = uint32_t(t / tiles_x) * tile;
        for (uint32_t y = 0; y < tile; ++y)
            for (uint32_t x = 0; x < tile; ++x)
                for (uint32_t c = 0; c < channels; ++c)
                    out[(size_t(oy + y) * out_width + ox + x) * channels + c] =
                        image[(size_t(tiles[t].y + y) * width + tiles[t].x + x) * channels + c];
    }
    return out;
}

}  // namespace lc::client
