#pragma once
// The client's scene: what it loads from glTF, renders, edits and bakes.
// Geometry is flattened to world space at load time.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "lightcuts/environment.h"
#include "lightcuts/guid.h"
#include "lightcuts/scene_light.h"

namespace lc {

struct Texture {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba8;
    // Base colour and emissive textures are sRGB-encoded; metallic-roughness
    // textures hold linear data (G: roughness, B: metallic).
    bool srgb = true;
};

// glTF alphaMode: OPAQUE ignores alpha, MASK cuts out where alpha (texture x
// factor) is under alpha_cutoff (in the image and in shadows), BLEND is drawn
// opaque and casts no shadow.
enum class AlphaMode : uint8_t { kOpaque, kMask, kBlend };

// The texture coordinates a material's textures are sampled with: the set
// (TEXCOORD_<set>) and KHR_texture_transform (scale, then rotation
// counter-clockwise in uv, then offset), applied to the mesh's uvs at load.
struct TextureCoordinates {
    int set = 0;
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians
    glm::vec2 scale{1.0f};
    bool transformed = false;  // the file gives KHR_texture_transform
};

struct Material {
    glm::vec4 base_color_factor{1.0f};
    int base_color_texture = -1;  // index into Scene::textures
    float metallic = 1.0f;        // glTF defaults
    float roughness = 1.0f;
    int metallic_roughness_texture = -1;  // scales roughness (G) and metallic (B)
    glm::vec3 emissive_factor{0.0f};
    int emissive_texture = -1;
    // A tangent-space normal map (linear RGB in [0, 1] -> [-1, 1]); its x and
    // y are scaled by normal_scale (glTF normalTexture.scale).
    int normal_texture = -1;
    float normal_scale = 1.0f;
    // False for surfaces light passes through (alphaMode BLEND, or a
    // KHR_materials_transmission factor > 0): they are drawn but block no light.
    bool casts_shadows = true;
    AlphaMode alpha_mode = AlphaMode::kOpaque;
    float alpha_cutoff = 0.5f;  // glTF's default; read for MASK only
    bool double_sided = false;
    TextureCoordinates texture_coordinates;
};

struct Mesh {
    std::vector<glm::vec3> positions;  // world space
    std::vector<glm::vec3> normals;    // world space, unit; generated when the file has none
    std::vector<glm::vec2> uvs;        // empty when the primitive has no TEXCOORD_0
    std::vector<uint32_t> indices;     // triangle list
    int material = -1;                 // -1: the glTF default material
    // World space: xyz unit, w = +-1 the bitangent's sign (glTF TANGENT, or
    // generated for a normal map); empty when the material has no normal map.
    std::vector<glm::vec4> tangents;
    std::vector<glm::vec4> colors;  // COLOR_0 (linear RGBA), empty: white
};

struct Camera {
    std::string name;
    glm::vec3 eye{0.0f, 0.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfov = 0.8f;  // radians
};

struct Scene {
    std::filesystem::path source;
    Guid guid;  // stable for a given content (see scene_guid.h)
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<SceneLight> lights;
    std::vector<Camera> cameras;
    glm::vec3 bounds_min{0.0f};  // of geometry and lights
    glm::vec3 bounds_max{0.0f};
    // The sky the file names (the client's gltf_environment.h), null: none;
    // environment_image is its map's file (empty for a sun and sky).
    std::shared_ptr<const Environment> environment;
    std::filesystem::path environment_image;
};

// Whether a mesh blocks light: its material's casts_shadows. A mesh without a
// valid material is drawn with glTF's default material, which does.
inline bool casts_shadows(const Scene& scene, const Mesh& mesh) {
    return mesh.material < 0 || size_t(mesh.material) >= scene.materials.size() ||
           scene.materials[size_t(mesh.material)].casts_shadows;
}

}  // namespace lc
