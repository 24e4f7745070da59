#pragma once
// tinygltf over a .gltf or .glb held in memory: the buffers and images are
// read through GltfResourceAccess (only what the options allow, each
// buffer file checked against its byteLength first), images are decoded
// after their bufferView is checked against its buffer, and an undecodable
// image becomes a warning (its textures are dropped), not a failed load.
// tinygltf's errors and warnings are passed on with the file's name, data:
// URIs shortened and each refused URI named.
#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <span>

#include "editor_client/scene/gltf_diagnostics.h"
#include "lightcuts/result.h"

namespace lc::client {

// `resource_folder` stands for the scene's folder (empty: no file is read);
// `allow_external`: any regular file may be read (gltf_resource_access.h).
Status parse_with_tinygltf(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder,
                           bool allow_external, tinygltf::Model& model, GltfDiagnostics& diagnostics);

}  // namespace lc::client
