#pragma once
// glTF textures -> Scene::textures: each (image, colour space) pair becomes
// one RGBA8 texture the first time a material uses it. An image used as
// colour (sRGB) and as data (linear) becomes two textures; an image with no
// usable pixels is dropped with a warning and its users sample no texture.
#include <tiny_gltf.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "editor_client/scene/gltf_diagnostics.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

class GltfTextureReader {
public:
    // `textures` receives the new textures; all three outlive the reader.
    GltfTextureReader(const tinygltf::Model& model, GltfDiagnostics& diagnostics,
                      std::vector<Texture>& textures)
        : model_(model), diagnostics_(diagnostics), textures_(textures) {}

    // The Scene::textures index for `info` (-1: none or unusable). `what`
    // names the use in messages; `srgb`: colour data (base colour,
    // emissive) rather than linear data (metallic-roughness, normals).
    Result<int> texture_for(const tinygltf::TextureInfo& info, const std::string& what, bool srgb = true);

private:
    int add_texture(int image_index, bool srgb, const std::string& what);

    const tinygltf::Model& model_;
    GltfDiagnostics& diagnostics_;
    std::vector<Texture>& textures_;
    std::map<std::pair<int, bool>, int> image_to_texture_;  // (glTF image, sRGB) -> textures_
};

}  // namespace lc::client
