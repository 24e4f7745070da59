#pragma once
// Alpha-masked surfaces (glTF alphaMode MASK) as shadow rays see them: a
// texel of the base colour texture's alpha, fetched nearest with repeat, keeps
// the surface (blocks light) when alpha x baseColorFactor.a >= alphaCutoff.
// The CPU (ShadowBvh::occluded) and the shaders (shadow_rays.glsl) decide
// with the same integer threshold, so they agree texel for texel.
#include <glm/vec2.hpp>

#include <cstdint>
#include <optional>
#include <vector>

#include "lightcuts/scene.h"

namespace lc {

// No 8-bit alpha reaches the cutoff: the surface is cut out everywhere.
inline constexpr uint32_t kMaskKeepsNothing = 256;

struct AlphaMask {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> alpha;  // row-major, row 0 at v = 0 (glTF's top)
    // The least 8-bit alpha that keeps the surface (0..kMaskKeepsNothing).
    uint32_t keep_threshold = 0;

    bool operator==(const AlphaMask&) const = default;
};

// The occluder triangles' masks: empty `triangle_mask` means every triangle
// is opaque; otherwise one entry per triangle (-1: opaque) and three texture
// coordinates per triangle (already through the texture's transform).
struct OccluderMasks {
    std::vector<AlphaMask> masks;
    std::vector<int32_t> triangle_mask;
    std::vector<glm::vec2> triangle_uvs;

    bool operator==(const OccluderMasks&) const = default;
    bool any() const { return !triangle_mask.empty(); }
};

// The least 8-bit alpha a with (a / 255) * factor >= cutoff, in float as the
// G-buffer compares; kMaskKeepsNothing when none.
uint32_t mask_keep_threshold(float alpha_factor, float cutoff);

// The mask a MASK material casts through, or nothing when its shadow is
// solid (no usable base colour texture and a factor that keeps the surface)
// or the material is not MASK. A factor under the cutoff without a texture
// gives a 1x1 mask that keeps nothing.
std::optional<AlphaMask> alpha_mask_of(const Scene& scene, const Material& material);

// No texel keeps the surface: it blocks no light anywhere.
inline bool mask_cuts_everything(const AlphaMask& mask) {
    return mask.keep_threshold >= kMaskKeepsNothing;
}

// One entry per mesh: the index in `masks` of the mask its material casts
// through (appended once per material), or -1 for a solid shadow.
std::vector<int32_t> mesh_alpha_masks(const Scene& scene, std::vector<AlphaMask>& masks);

// Records one occluder triangle (mesh vertex indices `corners`) with mask
// `mask` (-1: opaque). The per-triangle lists start when the first masked
// triangle comes, the opaque ones before it filled in then.
void add_occluder_mask(OccluderMasks& out, size_t triangle, const Mesh& mesh, const uint32_t* corners,
                       int32_t mask);

// The row-major index of the texel at uv in a width x height texture (both
// > 0): nearest, repeat wrap (the float math the shaders do).
size_t mask_texel_index(uint32_t width, uint32_t height, glm::vec2 uv);
// The texel at uv.
uint32_t mask_texel(const AlphaMask& mask, glm::vec2 uv);
inline bool mask_keeps(const AlphaMask& mask, glm::vec2 uv) {
    return mask_texel(mask, uv) >= mask.keep_threshold;
}

}  // namespace lc
