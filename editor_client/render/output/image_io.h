#pragma once
// Image files the renderer writes: 8-bit PNG (stb_image_write) and linear
// float PFM (for measurement), plus a PFM reader for tests and tools.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "lightcuts/result.h"

namespace lc::client {

// Rows top to bottom, 4 bytes per pixel (RGBA).
Status write_png(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 std::span<const uint8_t> rgba8);

struct FloatImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> rgb;  // rows top to bottom, 3 floats per pixel
};

// Colour PFM ("PF", little-endian scale -1). PFM stores rows bottom to top;
// `image` is top to bottom and is flipped on the way out (and back in).
Status write_pfm(const std::filesystem::path& path, const FloatImage& image);
Result<FloatImage> read_pfm(const std::filesystem::path& path);

// Reads an 8-bit PNG as RGBA (tests look at rendered images).
struct Rgba8Image {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;
};
Result<Rgba8Image> read_png(const std::filesystem::path& path);

}  // namespace lc::client
