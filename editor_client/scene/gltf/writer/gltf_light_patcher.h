#pragma once
// Copies the glTF at `source` to `out` with its punctual lights replaced by
// `lights`; everything else in the file is kept. Light references are removed
// from the source's nodes; root nodes that only held a light are reused for
// the new lights and further lights get new root nodes in the scene the
// loader draws. Relative URIs are rewritten for `out`'s folder
// (gltf_uri_rewrite.h), and a .glb source's binary chunk is embedded as
// base64 when `out` is .gltf.
#include <filesystem>
#include <span>

#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

Status write_lights_into_gltf(const std::filesystem::path& source, std::span<const SceneLight> lights,
                              const std::filesystem::path& out);

}  // namespace lc::client
