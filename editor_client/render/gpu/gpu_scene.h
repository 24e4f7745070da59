#pragma once
// The scene's geometry and materials on the GPU: one vertex and one index
// buffer for every mesh, textures, and one descriptor set per material (base
// colour, emissive and metallic-roughness textures; a white texel stands in
// for none).
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lightcuts/tree/gpu_layout.h"
#include "lightcuts/scene.h"
#include "editor_client/vk/buffer.h"
#include "editor_client/vk/context.h"
#include "editor_client/vk/descriptor_set.h"
#include "editor_client/vk/image.h"
#include "editor_client/vk/sampler.h"
#include "lightcuts/result.h"

namespace lc::client {

// Vertex layout of the G-buffer pass (binding 0, interleaved).
struct GpuVertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};
    glm::vec2 uv{0.0f};
    glm::vec4 tangent{0.0f};  // xyz, w: bitangent sign; zero without a normal map
    glm::vec4 color{1.0f};    // COLOR_0, times the base colour
};
static_assert(sizeof(GpuVertex) == 64);
// Primary rays read the same buffer as GpuSceneVertex (gpu_structs.h).
static_assert(sizeof(GpuSceneVertex) == sizeof(GpuVertex) && offsetof(GpuVertex, normal) == 12 &&
              offsetof(GpuVertex, uv) == 24 && offsetof(GpuVertex, tangent) == 32 &&
              offsetof(GpuVertex, color) == 48);

struct GpuDraw {
    uint32_t first_index = 0;
    uint32_t index_count = 0;
    int32_t vertex_offset = 0;
    uint32_t material = 0;  // index into GpuScene::materials (the last one is glTF's default)
    bool vertex_colors = false;  // the mesh has COLOR_0 (kDrawVertexColors)
};

struct GpuMaterial {
    VkDescriptorSet set = VK_NULL_HANDLE;
    glm::vec4 base_color_factor{1.0f};
    glm::vec3 emissive_factor{0.0f};
    float metallic = 1.0f;
    float roughness = 1.0f;
    uint32_t flags = 0;         // kDraw* bits (gpu_layout.h)
    float alpha_cutoff = 0.0f;  // with kDrawAlphaMask
    float normal_scale = 1.0f;  // with kDrawNormalTexture
};

class GpuScene {
public:
    // Checks the meshes (index ranges, attribute counts, finite positions) and
    // uploads them; an error names the mesh and the problem.
    static Result<GpuScene> upload(const vk::Context& context, const Scene& scene);

    // Vertex (and storage: primary rays read it) buffer of GpuVertex.
    VkBuffer vertex_buffer() const { return vertices_.handle(); }
    VkBuffer index_buffer() const { return indices_.handle(); }
    const std::vector<GpuDraw>& draws() const { return draws_; }
    const std::vector<GpuMaterial>& materials() const { return materials_; }
    const vk::DescriptorSetLayout& material_layout() const { return material_layout_; }

private:
    Status upload_geometry(const vk::Context& context, const Scene& scene);
    Status upload_textures(const vk::Context& context, const Scene& scene);
    Status create_materials(const vk::Context& context, const Scene& scene);

    vk::Buffer vertices_;
    vk::Buffer indices_;
    std::vector<GpuDraw> draws_;
    std::vector<vk::Image> textures_;  // scene textures, then the white texel
    vk::Sampler sampler_;
    vk::DescriptorSetLayout material_layout_;
    vk::DescriptorPool material_pool_;
    std::vector<GpuMaterial> materials_;
};

}  // namespace lc::client
