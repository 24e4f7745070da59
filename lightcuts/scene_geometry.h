#pragma once
// The scene's surfaces as the server sees them: a flat list of world-space
// triangles with one material each. This is what travels on the geometry
// channel and what the server's ray caster, area-light sampler and indirect
// solvers read. Textures are already reduced to per-triangle colours here;
// alpha masks travel as keep bits (surface_mask.h).
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

#include "lightcuts/surface_mask.h"

namespace lc {

struct SurfaceMaterial {
    glm::vec3 base_color{1.0f};  // linear RGB; the solvers reflect bake::bounce_albedo of it
    // Emitted radiance, linear RGB: glTF emissiveFactor times
    // KHR_materials_emissive_strength (times the texture's reduction).
    glm::vec3 emission{0.0f};
    float metallic = 0.0f;
    float roughness = 1.0f;
};

struct SurfaceTriangle {
    glm::vec3 positions[3]{};
    glm::vec3 normals[3]{};  // unit; equal for a flat (per-face) triangle
    uint32_t material = 0;   // index into SceneGeometry::materials
};

struct SceneGeometry {
    std::vector<SurfaceTriangle> triangles;
    std::vector<SurfaceMaterial> materials;
    // Alpha-masked (glTF MASK) triangles, by increasing triangle index: rays
    // pass them where the mask cuts the surface out. Empty: all opaque.
    std::vector<SurfaceMask> masks;
    std::vector<MaskedTriangle> masked_triangles;
};

// Twice the area's vector (unnormalised geometric normal, winding order).
glm::vec3 triangle_cross(const SurfaceTriangle& t);
float triangle_area(const SurfaceTriangle& t);
// Zero or non-finite area: no ray can hit it and no light can leave it.
bool is_degenerate(const SurfaceTriangle& t);

}  // namespace lc
