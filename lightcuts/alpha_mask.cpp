#include "lightcuts/alpha_mask.h"

#include <algorithm>
#include <cmath>

namespace lc {

uint32_t mask_keep_threshold(float alpha_factor, float cutoff) {
    for (uint32_t a = 0; a < kMaskKeepsNothing; ++a)
        if (float(a) / 255.0f * alpha_factor >= cutoff) return a;
    return kMaskKeepsNothing;
}

std::optional<AlphaMask> alpha_mask_of(const Scene& scene, const Material& material) {
    if (material.alpha_mode != AlphaMode::kMask) return std::nullopt;
    const float factor = material.base_color_factor.a;
    const int t = material.base_color_texture;
    const bool textured = t >= 0 && size_t(t) < scene.textures.size() &&
                          scene.textures[size_t(t)].width > 0 && scene.textures[size_t(t)].height > 0;
    AlphaMask mask;
    mask.keep_threshold = mask_keep_threshold(factor, material.alpha_cutoff);
    if (!textured) {
        // Without a texture the factor alone decides, everywhere.
        if (factor >= material.alpha_cutoff) return std::nullopt;
        mask.width = mask.height = 1;
        mask.alpha = {255};
        mask.keep_threshold = kMaskKeepsNothing;
        return mask;
    }
    const Texture& texture = scene.textures[size_t(t)];
    const size_t texels = size_t(texture.width) * size_t(texture.height);
    if (texture.rgba8.size() != 4 * texels) return std::nullopt;
    mask.width = texture.width;
    mask.height = texture.height;
    mask.alpha.resize(texels);
    for (size_t i = 0; i < texels; ++i) mask.alpha[i] = texture.rgba8[4 * i + 3];
    // Every texel kept: the shadow is solid and needs no fetch.
    if (*std::min_element(mask.alpha.begin(), mask.alpha.end()) >= mask.keep_threshold) return std::nullopt;
    return mask;
}

std::vector<int32_t> mesh_alpha_masks(const Scene& scene, std::vector<AlphaMask>& masks) {
    std::vector<int32_t> of_material(scene.materials.size(), -1);
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        std::optional<AlphaMask> mask = alpha_mask_of(scene, scene.materials[m]);
        if (!mask) continue;
        of_material[m] = int32_t(masks.size());
        masks.push_back(std::move(*mask));
    }
    std::vector<int32_t> of_mesh(scene.meshes.size(), -1);
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        const int material = scene.meshes[i].material;
        if (material >= 0 && size_t(material) < of_material.size())
            of_mesh[i] = of_material[size_t(material)];
    }
    return of_mesh;
}

void add_occluder_mask(OccluderMasks& out, size_t triangle, const Mesh& mesh, const uint32_t* corners,
                       int32_t mask) {
    if (mask < 0 && out.triangle_mask.empty()) return;
    if (out.triangle_mask.size() < triangle) {
        out.triangle_mask.resize(triangle, -1);
        out.triangle_uvs.resize(3 * triangle, glm::vec2(0.0f));
    }
    out.triangle_mask.push_back(mask);
    for (int k = 0; k < 3; ++k) {
        const uint32_t i = corners[k];
        out.triangle_uvs.push_back(mask >= 0 && i < mesh.uvs.size() ? mesh.uvs[i] : glm::vec2(0.0f));
    }
}

size_t mask_texel_index(uint32_t width, uint32_t height, glm::vec2 uv) {
    const float u = uv.x - std::floor(uv.x);
    const float v = uv.y - std::floor(uv.y);
    // NaN coordinates land on texel 0 (the casts are clamped first).
    const float fx = std::clamp(u * float(width), 0.0f, float(width - 1));
    const float fy = std::clamp(v * float(height), 0.0f, float(height - 1));
    const uint32_t x = std::isnan(fx) ? 0u : uint32_t(fx);
    const uint32_t y = std::isnan(fy) ? 0u : uint32_t(fy);
    return size_t(y) * size_t(width) + x;
}

uint32_t mask_texel(const AlphaMask& mask, glm::vec2 uv) {
    if (mask.alpha.empty()) return 255;
    return mask.alpha[mask_texel_index(uint32_t(mask.width), uint32_t(mask.height), uv)];
}

}  // namespace lc
