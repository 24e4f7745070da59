#pragma once
// Writes scenes back to glTF 2.0 with KHR_lights_punctual. The output's
// format follows its extension: .glb is binary, anything else is .gltf JSON
// with base64-embedded buffers. Files are written to a temporary name first and
// renamed, so a failed write never leaves half a file.
//
// Each light gets its own node (position as translation, direction as the
// rotation taking -Z onto it) carrying extras.lightcuts_guid, so the loader
// gives it back the same GUID, and extras.lightcuts_classic when classic.
#include <filesystem>
#include <span>

#include "lightcuts/scene.h"
#include "lightcuts/result.h"

namespace lc::client {

// A new, self-contained file: the world-space geometry (one node per mesh),
// material factors (textures are not written), cameras and lights.
Status write_scene_gltf(const Scene& scene, const std::filesystem::path& out);

// Copies the glTF at `source` to `out` with its punctual lights replaced by
// `lights`; everything else in the file is kept. Light references are removed
// from the source's nodes; root nodes that only held a light are reused for
// the new lights and further lights get new root nodes in the scene the
// loader draws. Relative URIs are rewritten for `out`'s folder, and a .glb
// source's binary chunk is embedded as base64 when `out` is .gltf.
Status write_lights_into_gltf(const std::filesystem::path& source,
                              std::span<const SceneLight> lights, const std::filesystem::path& out);

}  // namespace lc::client
