#include "editor_client/render/output/image_io.h"

#include <bit>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <system_error>

// stb's implementations live in this file only. STB_*_STATIC keeps their
// symbols private to it, so another library's copy (tinygltf) cannot clash.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>
#pragma GCC diagnostic pop

namespace lc::client {
namespace {

// Writes to a temporary name, then renames: a failed write leaves no half file.
Status write_atomically(const std::filesystem::path& path,
                        const std::function<bool(const std::filesystem::path&)>& write) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    if (!write(tmp)) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        return make_error("cannot write " + path.string());
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec)
        return make_error("cannot rename " + tmp.string() + " to " + path.string() + ": " +
                          ec.message());
    return Ok{};
}

}  // namespace

Status write_png(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 std::span<const uint8_t> rgba8) {
    if (width == 0 || height == 0 || rgba8.size() != size_t(width) * height * 4)
        return make_error("write_png " + path.string() + ": pixel data does not match " +
                          std::to_string(width) + "x" + std::to_string(height));
    return write_atomically(path, [&](const std::filesystem::path& tmp) {
        return stbi_write_png(tmp.c_str(), int(width), int(height), 4, rgba8.data(),
                              int(width * 4)) != 0;
    });
}

Status write_pfm(const std::filesystem::path& path, const FloatImage& image) {
    if (image.width == 0 || image.height == 0 ||
        image.rgb.size() != size_t(image.width) * image.height * 3)
        return make_error("write_pfm " + path.string() + ": pixel data does not match " +
                          std::to_string(image.width) + "x" + std::to_string(image.height));
    static_assert(std::endian::native == std::endian::little, "PFM writer assumes little-endian");
    return write_atomically(path, [&](const std::filesystem::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) return false;
        out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
        const size_t row_floats = size_t(image.width) * 3;
        for (uint32_t y = image.height; y-- > 0;) {
            out.write(reinterpret_cast<const char*>(image.rgb.data() + y * row_floats),
                      std::streamsize(row_floats * sizeof(float)));
        }
        return static_cast<bool>(out.flush());
    });
}

Result<FloatImage> read_pfm(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error("cannot open " + path.string());
    std::string magic;
    long long width = 0, height = 0;
    double scale = 0.0;
    in >> magic >> width >> height >> scale;
    if (!in || magic != "PF") return make_error(path.string() + ": not a colour PFM (magic 'PF')");
    if (width <= 0 || height <= 0 || width > 65536 || height > 65536)
        return make_error(path.string() + ": PFM size " + std::to_string(width) + "x" +
                          std::to_string(height) + " is out of range");
    if (scale >= 0.0) return make_error(path.string() + ": big-endian PFM is not supported");
    in.get();  // the single whitespace byte after the header
    FloatImage image;
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.rgb.resize(size_t(width) * height * 3);
    const size_t row_floats = size_t(width) * 3;
    for (uint32_t y = image.height; y-- > 0;) {
        in.read(reinterpret_cast<char*>(image.rgb.data() + y * row_floats),
                std::streamsize(row_floats * sizeof(float)));
        if (!in) return make_error(path.string() + ": PFM pixel data is truncated");
    }
    return image;
}

Result<Rgba8Image> read_png(const std::filesystem::path& path) {
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &channels, 4),
                                                     stbi_image_free);
    if (!pixels)
        return make_error("cannot read PNG " + path.string() + ": " + stbi_failure_reason());
    Rgba8Image image;
    image.width = uint32_t(w);
    image.height = uint32_t(h);
    image.rgba.assign(pixels.get(), pixels.get() + size_t(w) * h * 4);
    return image;
}

}  // namespace lc::client
