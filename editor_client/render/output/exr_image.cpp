#include "editor_client/render/output/exr_image.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <Imath/half.h>

#include <algorithm>
#include <cctype>
#include <exception>
#include <system_error>
#include <type_traits>
#include <vector>

namespace lc::client {
namespace {

constexpr const char* kChannels[3] = {"R", "G", "B"};

// Slices over an interleaved RGB buffer of `T` (float or half) whose first pixel is the data
// window's origin. OpenEXR writes only the pixel type of the file's channels.
template <typename T>
Imf::FrameBuffer rgb_slices(T* rgb, uint32_t width, const Imath::Box2i& window) {
    const Imf::PixelType type = std::is_same_v<T, half> ? Imf::HALF : Imf::FLOAT;
    const size_t x_stride = 3 * sizeof(T);
    const size_t y_stride = x_stride * width;
    // OpenEXR addresses pixel (x, y) as base + x * x_stride + y * y_stride, window origin included.
    char* base = reinterpret_cast<char*>(rgb) - ptrdiff_t(window.min.x) * ptrdiff_t(x_stride) -
                 ptrdiff_t(window.min.y) * ptrdiff_t(y_stride);
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c) frame.insert(kChannels[c], Imf::Slice(type, base + c * sizeof(T), x_stride, y_stride));
    return frame;
}

}  // namespace

bool is_exr_path(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".exr";
}

Status write_exr(const std::filesystem::path& path, const FloatImage& image, const ExrWriteOptions& options) {
    if (image.width == 0 || image.height == 0 || image.rgb.size() != size_t(image.width) * image.height * 3)
        return make_error("write_exr " + path.string() + ": pixel data does not match " +
                          std::to_string(image.width) + "x" + std::to_string(image.height));
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    try {
        Imf::Header header(int(image.width), int(image.height));
        header.compression() = Imf::ZIP_COMPRESSION;
        const Imf::PixelType type = options.pixels == ExrPixels::kHalf ? Imf::HALF : Imf::FLOAT;
        for (const char* channel : kChannels) header.channels().insert(channel, Imf::Channel(type));
        for (const auto& [name, text] : options.attributes) header.insert(name, Imf::StringAttribute(text));
        Imf::OutputFile out(tmp.c_str(), header);
        // Half: each value rounded to the nearest half (Imath's conversion) before it is written.
        std::vector<half> halves;
        if (type == Imf::HALF) {
            halves.assign(image.rgb.begin(), image.rgb.end());
            out.setFrameBuffer(rgb_slices(halves.data(), image.width, header.dataWindow()));
        } else {
            // OpenEXR only reads through the slices; its API takes a mutable base pointer.
            float* pixels = const_cast<float*>(image.rgb.data());
            out.setFrameBuffer(rgb_slices(pixels, image.width, header.dataWindow()));
        }
        out.writePixels(int(image.height));
    } catch (const std::exception& e) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        return make_error("cannot write EXR " + path.string() + ": " + e.what());
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) return make_error("cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message());
    return Ok{};
}

Result<FloatImage> read_exr(const std::filesystem::path& path) {
    try {
        Imf::InputFile in(path.c_str());
        const Imath::Box2i window = in.header().dataWindow();
        for (const char* channel : kChannels)
            if (!in.header().channels().findChannel(channel))
                return make_error(path.string() + ": EXR has no " + channel + " channel");
        FloatImage image;
        image.width = uint32_t(window.max.x - window.min.x + 1);
        image.height = uint32_t(window.max.y - window.min.y + 1);
        image.rgb.resize(size_t(image.width) * image.height * 3);
        in.setFrameBuffer(rgb_slices(image.rgb.data(), image.width, window));
        in.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const std::exception& e) {
        return make_error("cannot read EXR " + path.string() + ": " + e.what());
    }
}

Result<std::string> read_exr_attribute(const std::filesystem::path& path, const std::string& name) {
    try {
        Imf::InputFile in(path.c_str());
        const auto* attribute = in.header().findTypedAttribute<Imf::StringAttribute>(name);
        if (!attribute) return make_error(path.string() + ": EXR header has no string attribute '" + name + "'");
        return attribute->value();
    } catch (const std::exception& e) {
        return make_error("cannot read EXR " + path.string() + ": " + e.what());
    }
}

}  // namespace lc::client
