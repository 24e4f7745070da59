#include "editor_client/render/gpu/gpu_scene.h"

#include <array>
#include <cmath>
#include <string>

#include "lightcuts/device/bindings.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

std::string mesh_name(size_t index) { return "mesh " + std::to_string(index); }

Status check_mesh(const Mesh& mesh, size_t index) {
    const size_t n = mesh.positions.size();
    if (!mesh.normals.empty() && mesh.normals.size() != n)
        return make_error(mesh_name(index) + ": " + std::to_string(mesh.normals.size()) +
                          " normals for " + std::to_string(n) + " positions");
    if (!mesh.uvs.empty() && mesh.uvs.size() != n)
        return make_error(mesh_name(index) + ": " + std::to_string(mesh.uvs.size()) +
                          " texture coordinates for " + std::to_string(n) + " positions");
    if (!mesh.colors.empty() && mesh.colors.size() != n)
        return make_error(mesh_name(index) + ": " + std::to_string(mesh.colors.size()) +
                          " vertex colours for " + std::to_string(n) + " positions");
    if (!mesh.tangents.empty() && mesh.tangents.size() != n)
        return make_error(mesh_name(index) + ": " + std::to_string(mesh.tangents.size()) + " tangents for " +
                          std::to_string(n) + " positions");
    if (mesh.indices.size() % 3 != 0)
        return make_error(mesh_name(index) + ": index count " +
                          std::to_string(mesh.indices.size()) + " is not a multiple of 3");
    for (uint32_t i : mesh.indices)
        if (i >= n)
            return make_error(mesh_name(index) + ": index " + std::to_string(i) +
                              " is out of range (" + std::to_string(n) + " vertices)");
    for (const glm::vec3& p : mesh.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return make_error(mesh_name(index) + ": a vertex position is not finite");
    return Ok{};
}

Result<vk::Image> upload_texture(const vk::Context& context, const Texture& texture, size_t index) {
    if (texture.width <= 0 || texture.height <= 0 ||
        texture.rgba8.size() != size_t(texture.width) * size_t(texture.height) * 4)
        return make_error("texture " + std::to_string(index) + ": " +
                          std::to_string(texture.rgba8.size()) + " bytes for " +
                          std::to_string(texture.width) + "x" + std::to_string(texture.height) +
                          " RGBA8");
    vk::ImageDesc desc;
    desc.width = uint32_t(texture.width);
    desc.height = uint32_t(texture.height);
    // Base colour and emissive textures are sRGB-encoded: the format decodes them.
    desc.format = texture.srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    Result<vk::Image> image = vk::Image::create(context.device(), desc);
    if (!image) return make_error(image.error());
    LC_RETURN_IF_ERROR(vk::upload_image(context.device(), context.command_pool(), *image,
                                        std::as_bytes(std::span(texture.rgba8)),
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
    return std::move(image).value();
}


// Every mesh's vertices as GpuVertex, appended after `vertices`.
void append_vertices(const Mesh& mesh, std::vector<GpuVertex>& vertices) {
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        GpuVertex vertex;
        vertex.position = mesh.positions[v];
        if (!mesh.normals.empty()) vertex.normal = mesh.normals[v];
        if (!mesh.uvs.empty()) vertex.uv = mesh.uvs[v];
        if (!mesh.tangents.empty()) vertex.tangent = mesh.tangents[v];
        if (!mesh.colors.empty()) vertex.color = mesh.colors[v];
        vertices.push_back(vertex);
    }
}

// A material's factors and flags, its textures not yet bound.
GpuMaterial material_factors(const Material& material) {
    GpuMaterial out;
    out.base_color_factor = material.base_color_factor;
    out.emissive_factor = material.emissive_factor;
    out.metallic = material.metallic;
    out.roughness = material.roughness;
    if (!material.double_sided) out.flags |= kDrawSingleSided;
    if (material.alpha_mode == AlphaMode::kMask) {
        out.flags |= kDrawAlphaMask;
        out.alpha_cutoff = material.alpha_cutoff;
    }
    out.normal_scale = material.normal_scale;
    return out;
}

}  // namespace

Result<GpuScene> GpuScene::upload(const vk::Context& context, const Scene& scene) {
    GpuScene gpu;
    LC_RETURN_IF_ERROR(gpu.upload_geometry(context, scene));
    LC_RETURN_IF_ERROR(gpu.upload_textures(context, scene));
    LC_RETURN_IF_ERROR(gpu.create_materials(context, scene));
    return gpu;
}

// Geometry: every mesh appended to one vertex and one index buffer.
Status GpuScene::upload_geometry(const vk::Context& context, const Scene& scene) {
    std::vector<GpuVertex> vertices;
    std::vector<uint32_t> indices;
    const uint32_t default_material = uint32_t(scene.materials.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        LC_RETURN_IF_ERROR(check_mesh(mesh, m));
        if (mesh.indices.empty()) continue;
        if (vertices.size() + mesh.positions.size() > size_t(INT32_MAX) ||
            indices.size() + mesh.indices.size() > size_t(UINT32_MAX))
            return make_error("the scene has too many vertices or indices for one draw buffer");
        GpuDraw draw;
        draw.first_index = uint32_t(indices.size());
        draw.index_count = uint32_t(mesh.indices.size());
        draw.vertex_offset = int32_t(vertices.size());
        draw.vertex_colors = !mesh.colors.empty();
        draw.material = mesh.material >= 0 && size_t(mesh.material) < scene.materials.size()
                            ? uint32_t(mesh.material)
                            : default_material;
        append_vertices(mesh, vertices);
        indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
        draws_.push_back(draw);
    }
    const vk::Device& device = context.device();
    Result<vk::Buffer> vertex_buffer = vk::Buffer::create_with_data(
        device, context.command_pool(), std::as_bytes(std::span(vertices)),
        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);  // primary rays read it too
    if (!vertex_buffer) return make_error(vertex_buffer.error());
    vertices_ = std::move(vertex_buffer).value();
    Result<vk::Buffer> index_buffer = vk::Buffer::create_with_data(
        device, context.command_pool(), std::as_bytes(std::span(indices)),
        VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    if (!index_buffer) return make_error(index_buffer.error());
    indices_ = std::move(index_buffer).value();
    return Ok{};
}

// Textures, then one white texel for materials without one, and their sampler.
Status GpuScene::upload_textures(const vk::Context& context, const Scene& scene) {
    for (size_t t = 0; t < scene.textures.size(); ++t) {
        Result<vk::Image> image = upload_texture(context, scene.textures[t], t);
        if (!image) return make_error(image.error());
        textures_.push_back(std::move(image).value());
    }
    Texture white;
    white.width = white.height = 1;
    white.rgba8 = {255, 255, 255, 255};
    Result<vk::Image> white_image = upload_texture(context, white, scene.textures.size());
    if (!white_image) return make_error(white_image.error());
    textures_.push_back(std::move(white_image).value());

    Result<vk::Sampler> sampler = vk::Sampler::create_linear_repeat(context.device().handle());
    if (!sampler) return make_error(sampler.error());
    sampler_ = std::move(sampler).value();
    return Ok{};
}

// Scene materials, then glTF's default material (white, metallic 1, roughness
// 1), each with a descriptor set of its four textures.
Status GpuScene::create_materials(const vk::Context& context, const Scene& scene) {
    VkDevice device = context.device().handle();
    std::array<VkDescriptorType, kMaterialBindingCount> types{};
    types.fill(VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    Result<vk::DescriptorSetLayout> layout =
        vk::DescriptorSetLayout::create(device, types, VK_SHADER_STAGE_FRAGMENT_BIT);
    if (!layout) return make_error(layout.error());
    material_layout_ = std::move(layout).value();

    std::vector<Material> materials = scene.materials;
    materials.push_back(Material{});
    const uint32_t set_count = uint32_t(materials.size());
    std::array<VkDescriptorPoolSize, 1> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kMaterialBindingCount * set_count}};
    Result<vk::DescriptorPool> pool = vk::DescriptorPool::create(device, set_count, sizes);
    if (!pool) return make_error(pool.error());
    material_pool_ = std::move(pool).value();

    const size_t white_index = textures_.size() - 1;
    auto texture_index = [&](int index, uint32_t flag, uint32_t& flags) {
        if (index >= 0 && size_t(index) < scene.textures.size()) {
            flags |= flag;
            return size_t(index);
        }
        return white_index;
    };
    for (const Material& material : materials) {
        GpuMaterial out = material_factors(material);
        size_t base = texture_index(material.base_color_texture, kDrawBaseColorTexture, out.flags);
        size_t emissive = texture_index(material.emissive_texture, kDrawEmissiveTexture, out.flags);
        size_t metallic_roughness = texture_index(material.metallic_roughness_texture,
                                                  kDrawMetallicRoughnessTexture, out.flags);
        size_t normal = texture_index(material.normal_texture, kDrawNormalTexture, out.flags);
        Result<VkDescriptorSet> set = material_pool_.allocate(material_layout_);
        if (!set) return make_error(set.error());
        out.set = *set;
        vk::DescriptorWriter(out.set)
            .sampled_image(kBindBaseColorTexture, textures_[base].view(), sampler_.handle())
            .sampled_image(kBindEmissiveTexture, textures_[emissive].view(), sampler_.handle())
            .sampled_image(kBindMetallicRoughnessTexture, textures_[metallic_roughness].view(),
                           sampler_.handle())
            .sampled_image(kBindNormalTexture, textures_[normal].view(), sampler_.handle())
            .update(device);
        materials_.push_back(out);
    }
    return Ok{};
}

}  // namespace lc::client
