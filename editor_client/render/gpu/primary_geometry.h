#pragma once
// What primary rays (PrimaryRaysPass) need of the scene, in GpuScene's order:
// every triangle's world-space vertices and its vertex indices in GpuScene's
// vertex buffer with its draw, and each draw's material as gbuffer.frag
// stores it. Textures are the raster pass's alone: primary_rays_unsupported
// names the first material that has one.
#include <glm/vec3.hpp>

#include <string>
#include <vector>

#include "editor_client/render/gpu/gpu_scene.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/scene.h"

namespace lc::client {

struct PrimaryGeometry {
    std::vector<glm::vec3> triangle_vertices;      // 3 per triangle
    std::vector<GpuPrimaryTriangle> triangles;     // the same triangles, by index
    std::vector<GpuSurfaceMaterial> draw_materials;  // per GpuScene draw
};

PrimaryGeometry primary_geometry(const Scene& scene, const GpuScene& gpu_scene);

// Why the scene's G-buffer cannot be cast as rays (a textured or alpha-masked
// material), empty when it can.
std::string primary_rays_unsupported(const GpuScene& gpu_scene);

}  // namespace lc::client
