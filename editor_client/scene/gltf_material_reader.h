#pragma once
// glTF materials -> Scene::materials (and the textures they use ->
// Scene::textures), in the file's order so primitives keep their indices.
// Read: the metallic-roughness factors and textures, emissive (with
// KHR_materials_emissive_strength), the normal texture and its scale, one set
// of texture coordinates (with KHR_texture_transform), alpha mode and cutoff,
// double-sidedness, and whether the surface hides light (blended or
// KHR_materials_transmission surfaces do not). Factors must be finite and
// non-negative; other surprises are warnings.
#include <tiny_gltf.h>

#include "editor_client/scene/gltf_diagnostics.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

Status read_gltf_materials(const tinygltf::Model& model, GltfDiagnostics& diagnostics, Scene& scene);

}  // namespace lc::client
