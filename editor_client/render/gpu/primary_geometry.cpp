#include "editor_client/render/gpu/primary_geometry.h"

namespace lc::client {
namespace {

// The draw flags gbuffer.frag samples a texture for, or discards by.
constexpr uint32_t kRasterOnlyFlags = kDrawBaseColorTexture | kDrawEmissiveTexture |
                                      kDrawMetallicRoughnessTexture | kDrawAlphaMask |
                                      kDrawNormalTexture;

GpuSurfaceMaterial surface_material(const GpuMaterial& material, bool vertex_colors) {
    GpuSurfaceMaterial m;
    m.base_color_factor = material.base_color_factor;
    m.emissive_metallic = glm::vec4(material.emissive_factor, material.metallic);
    m.roughness = material.roughness;
    m.flags = (vertex_colors ? kDrawVertexColors : 0u) | (material.flags & kDrawSingleSided);
    return m;
}

}  // namespace

PrimaryGeometry primary_geometry(const Scene& scene, const GpuScene& gpu_scene) {
    PrimaryGeometry g;
    // GpuScene::upload's order: meshes with indices, one draw each, their
    // vertices appended (a draw's vertex_offset is where its mesh's start).
    size_t draw = 0;
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.indices.empty()) continue;
        const GpuDraw& d = gpu_scene.draws()[draw];
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            GpuPrimaryTriangle t;
            t.v0 = uint32_t(d.vertex_offset) + mesh.indices[i];
            t.v1 = uint32_t(d.vertex_offset) + mesh.indices[i + 1];
            t.v2 = uint32_t(d.vertex_offset) + mesh.indices[i + 2];
            t.draw = uint32_t(draw);
            g.triangles.push_back(t);
            for (size_t k = 0; k < 3; ++k) g.triangle_vertices.push_back(mesh.positions[mesh.indices[i + k]]);
        }
        g.draw_materials.push_back(surface_material(gpu_scene.materials()[d.material], d.vertex_colors));
        ++draw;
    }
    return g;
}

std::string primary_rays_unsupported(const GpuScene& gpu_scene) {
    for (const GpuDraw& d : gpu_scene.draws()) {
        const GpuMaterial& material = gpu_scene.materials()[d.material];
        if ((material.flags & kRasterOnlyFlags) != 0u)
            return "material " + std::to_string(d.material) +
                   " has a texture or an alpha mask, which only the raster G-buffer samples";
    }
    return {};
}

}  // namespace lc::client
