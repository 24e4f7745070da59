#pragma once
// What `render` writes: the 8-bit or linear image (-o) and the linear one (--float).
#include <cstdint>
#include <vector>

#include "editor_client/commands/render_options.h"
#include "editor_client/commands/render_request.h"
#include "editor_client/render/output/render_stats.h"

namespace lc::client {

// One frame's image and statistics: the renderer's, or the mean of --spp eye rays.
struct RenderedFrame {
    RenderStats stats;
    std::vector<float> hdr;
    std::vector<uint8_t> display;
};


// -o and --float: the 8-bit image (an .exr -o: the linear one) and the linear one.
void write_images(const RenderOptions& options, const RenderRequest& request, const RenderedFrame& image);

}  // namespace lc::client
