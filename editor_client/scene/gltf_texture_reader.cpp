#include "editor_client/scene/gltf_texture_reader.h"

#include <algorithm>
#include <cstring>

namespace lc::client {
namespace {

namespace tg = tinygltf;

int bytes_per_channel(const tg::Image& image) {
    return image.bits == 16 ? 2 : (image.bits == 8 ? 1 : 0);
}

// Decoded pixels of a size, channel count and depth we can convert.
bool has_usable_pixels(const tg::Image& image) {
    const size_t expected = size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0)) *
                            size_t(std::max(image.component, 0)) * size_t(bytes_per_channel(image));
    return !image.image.empty() && image.width > 0 && image.height > 0 && image.component >= 1 &&
           image.component <= 4 && bytes_per_channel(image) != 0 && image.image.size() == expected;
}

// One pixel as RGBA8: 16-bit channels keep their high byte (little-endian
// storage), grey (+ alpha) is replicated to RGB.
void rgba8_of_pixel(const tg::Image& image, size_t pixel, uint8_t rgba[4]) {
    const int depth = bytes_per_channel(image);
    rgba[0] = rgba[1] = rgba[2] = 0;
    rgba[3] = 255;
    for (int c = 0; c < image.component; ++c) {
        const size_t at = (pixel * size_t(image.component) + size_t(c)) * size_t(depth);
        rgba[c] = depth == 2 ? image.image[at + 1] : image.image[at];
    }
    if (image.component == 1 || image.component == 2) {
        const uint8_t alpha = image.component == 2 ? rgba[1] : 255;
        rgba[1] = rgba[0];
        rgba[2] = rgba[0];
        rgba[3] = alpha;
    }
}

Texture texture_from(const tg::Image& image, bool srgb) {
    Texture out;
    out.srgb = srgb;
    out.width = image.width;
    out.height = image.height;
    const size_t pixels = size_t(image.width) * size_t(image.height);
    out.rgba8.resize(pixels * 4);
    for (size_t p = 0; p < pixels; ++p) rgba8_of_pixel(image, p, &out.rgba8[p * 4]);
    return out;
}

}  // namespace

Result<int> GltfTextureReader::texture_for(const tg::TextureInfo& info, const std::string& what, bool srgb) {
    if (info.index < 0) return -1;
    if (info.index >= static_cast<int>(model_.textures.size())) {
        return diagnostics_.fail(what + " uses texture " + std::to_string(info.index) +
                                 ", which does not exist");
    }
    const tg::Texture& texture = model_.textures[size_t(info.index)];
    if (texture.source < 0) {
        diagnostics_.warn(what + ": texture " + std::to_string(info.index) + " has no image; ignored");
        return -1;
    }
    if (texture.source >= static_cast<int>(model_.images.size())) {
        return diagnostics_.fail("texture " + std::to_string(info.index) + " uses image " +
                                 std::to_string(texture.source) + ", which does not exist");
    }
    auto found = image_to_texture_.find({texture.source, srgb});
    if (found != image_to_texture_.end()) return found->second;
    const int index = add_texture(texture.source, srgb, what);
    image_to_texture_[{texture.source, srgb}] = index;
    return index;
}

int GltfTextureReader::add_texture(int image_index, bool srgb, const std::string& what) {
    const tg::Image& image = model_.images[size_t(image_index)];
    if (!has_usable_pixels(image)) {
        diagnostics_.warn(what + ": image " + std::to_string(image_index) +
                          " has no usable pixels; the texture is ignored");
        return -1;
    }
    textures_.push_back(texture_from(image, srgb));
    return static_cast<int>(textures_.size()) - 1;
}

}  // namespace lc::client
