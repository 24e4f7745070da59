#include "editor_client/commands/render_output.h"

#include <string>

#include "editor_client/commands/command_errors.h"
#include "editor_client/render/output/exr_image.h"
#include "editor_client/render/output/image_io.h"
#include "lightcuts/version.h"

namespace lc::client {
namespace {

// The linear image: the RGB of the RGBA read-back.
FloatImage linear_image(const RenderRequest& request, const std::vector<float>& hdr) {
    FloatImage image;
    image.width = request.width;
    image.height = request.height;
    image.rgb.reserve(size_t(request.width) * request.height * 3);
    for (size_t i = 0; i < hdr.size(); i += 4) image.rgb.insert(image.rgb.end(), {hdr[i], hdr[i + 1], hdr[i + 2]});
    return image;
}

// An EXR's header says what made it: the program, the mode, the scene and the tone map's exposure.
ExrWriteOptions exr_options(const RenderOptions& options, const RenderStats& stats) {
    ExrWriteOptions exr;
    exr.pixels = options.exr_half ? ExrPixels::kHalf : ExrPixels::kFloat;
    exr.attributes = {{"software", std::string("editor_client ") + kVersion},
                      {"lightcuts.mode", stats.mode},
                      {"lightcuts.scene", options.scene},
                      {"lightcuts.lights", std::to_string(stats.lights)},
                      {"lightcuts.nodes", std::to_string(stats.nodes)},
                      {"lightcuts.exposure", std::to_string(stats.exposure)}};
    return exr;
}

// The linear image as the path's extension says: OpenEXR (.exr) or PFM.
void write_linear(const std::string& path, const FloatImage& image, const RenderOptions& options,
                  const RenderStats& stats) {
    Status written = is_exr_path(path) ? write_exr(path, image, exr_options(options, stats)) : write_pfm(path, image);
    if (!written) fail(written.error());
}


}  // namespace

// -o and --float: the 8-bit image (an .exr -o: the linear one) and the linear one.
void write_images(const RenderOptions& options, const RenderRequest& request, const RenderedFrame& image) {
    if (is_exr_path(options.output)) {
        write_linear(options.output, linear_image(request, image.hdr), options, image.stats);
    } else {
        Status png = write_png(options.output, request.width, request.height, image.display);
        if (!png) fail(png.error());
    }
    if (!options.float_output.empty())
        write_linear(options.float_output, linear_image(request, image.hdr), options, image.stats);
}

}  // namespace lc::client
