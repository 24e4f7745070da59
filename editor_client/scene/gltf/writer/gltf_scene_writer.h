#pragma once
// A scene as a new, self-contained glTF 2.0 file: the world-space geometry
// (one node per mesh: positions, normals, the first UV set, indices),
// material factors (textures are not written), perspective cameras, the
// environment (gltf_environment.h) and KHR_lights_punctual lights
// (gltf_light_json.h). .glb or .gltf by the extension (gltf_document_output.h).
#include <filesystem>

#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

Status write_scene_gltf(const Scene& scene, const std::filesystem::path& out);

}  // namespace lc::client
