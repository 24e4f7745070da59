#pragma once
// OpenEXR images of the renderer's linear radiance (Debian's libopenexr): the
// format compositors and other renderers exchange HDR images in. RGB channels,
// float (bit for bit the PFM's values) or half, ZIP-compressed (lossless),
// with the render's facts as string attributes in the header.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "editor_client/render/output/image_io.h"
#include "lightcuts/result.h"

namespace lc::client {

enum class ExrPixels { kFloat, kHalf };

struct ExrWriteOptions {
    ExrPixels pixels = ExrPixels::kFloat;
    // Header attributes (name, text), e.g. ("lightcuts.mode", "lightcuts").
    std::vector<std::pair<std::string, std::string>> attributes;
};

// True for a path ending in .exr (any case): the commands pick the format by extension.
bool is_exr_path(const std::filesystem::path& path);

// Writes `image` (rows top to bottom) to a temporary name, then renames it.
Status write_exr(const std::filesystem::path& path, const FloatImage& image, const ExrWriteOptions& options = {});

// Reads R, G and B of an EXR's data window as float (half channels widened).
Result<FloatImage> read_exr(const std::filesystem::path& path);

// A string attribute of an EXR's header; an error when the file or the attribute is missing.
Result<std::string> read_exr_attribute(const std::filesystem::path& path, const std::string& name);

}  // namespace lc::client
