#pragma once
// Alpha-masked surfaces as the server's ray caster sees them: one bit per
// texel (kept or cut out), decided on the client with the material's cutoff,
// and the masked triangles' texture coordinates. A ray passes a masked
// triangle where the texel under its hit is cut out, the same texel the
// client's shadow rays and G-buffer pick (alpha_mask.h's nearest, repeat).
#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

#include "lightcuts/alpha_mask.h"

namespace lc {

struct SurfaceMask {
    uint32_t width = 0;
    uint32_t height = 0;
    // Row-major texels, bit (i % 32) of word i / 32 set where the texel keeps the surface.
    std::vector<uint32_t> keep_bits;

    bool operator==(const SurfaceMask&) const = default;
};

// A triangle of SceneGeometry::triangles drawn with a mask: its corners'
// texture coordinates (through the texture's transform) and the mask.
struct MaskedTriangle {
    uint32_t triangle = 0;
    uint32_t mask = 0;  // index into SceneGeometry::masks
    glm::vec2 uvs[3]{};

    bool operator==(const MaskedTriangle&) const = default;
};

// 32-bit words of a width x height mask (0 when either is 0).
uint64_t surface_mask_words(uint64_t width, uint64_t height);

// The client's 8-bit mask reduced to keep bits with its threshold.
SurfaceMask surface_mask_of(const AlphaMask& mask);

// Whether the surface is kept (blocks light) at `uv`; a mask of no texels keeps it.
bool surface_mask_keeps(const SurfaceMask& mask, glm::vec2 uv);

// The point at barycentrics (u, v) of positions[1] and positions[2].
inline glm::vec2 masked_uv(const MaskedTriangle& t, float u, float v) {
    return (1.0f - u - v) * t.uvs[0] + u * t.uvs[1] + v * t.uvs[2];
}

}  // namespace lc
