#include "lightcuts/surface_mask.h"

namespace lc {

uint64_t surface_mask_words(uint64_t width, uint64_t height) { return (width * height + 31) / 32; }

SurfaceMask surface_mask_of(const AlphaMask& mask) {
    SurfaceMask out;
    out.width = uint32_t(mask.width);
    out.height = uint32_t(mask.height);
    out.keep_bits.assign(surface_mask_words(out.width, out.height), 0u);
    for (size_t i = 0; i < mask.alpha.size(); ++i)
        if (mask.alpha[i] >= mask.keep_threshold) out.keep_bits[i / 32] |= 1u << (i % 32);
    return out;
}

bool surface_mask_keeps(const SurfaceMask& mask, glm::vec2 uv) {
    if (mask.width == 0 || mask.height == 0) return true;
    const size_t i = mask_texel_index(mask.width, mask.height, uv);
    return (mask.keep_bits[i / 32] >> (i % 32)) & 1u;
}

}  // namespace lc
