#pragma once
// `render`'s flags checked against each other: the frame's settings, the
// sweeps, the strides and the eye rays per pixel.
#include <cstdint>
#include <optional>
#include <vector>

#include "editor_client/commands/render_options.h"
#include "editor_client/render/pixel_stride.h"
#include "editor_client/render/sweeps/realtime_sweep.h"
#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/supersampled_render.h"
#include "lightcuts/scene.h"

namespace lc::client {

// The side of a tile of --tile-stride: the renderer's workgroup, so a
// subgroup's pixels are the full frame's neighbours.
inline constexpr uint32_t kStrideTile = 8;

// What the command line asks for, checked: the frame's settings and how the
// written image is made from it.
struct RenderRequest {
    RenderSettings settings;
    bool error_mode = false;  // `error`: lightcuts shown as its error against the reference
    bool compare = false;     // also render the reference and measure the error
    std::vector<float> sweep_ratios;
    RealtimeSweepPlan realtime_sweep;  // --sweep-realtime, --sweep-frames, --sweep-path
    std::vector<uint32_t> sweep_blocks;  // --sweep-blocks
    uint32_t width = 0;  // the written image's size (a stride's is smaller than the frame's)
    uint32_t height = 0;
    std::vector<PixelRegion> tiles;  // --tile-stride: the tiles rendered
};

// The request, or a failure (fail()) naming the flag at fault.
RenderRequest make_request(const RenderOptions& options, const Scene& scene, bool has_tree_source);

// --spp and --spp-method, checked against the mode; none: one eye ray per pixel on the GPU.
std::optional<SupersampleRequest> supersample_request(const RenderOptions& options,
                                                      const RenderRequest& request);

}  // namespace lc::client
