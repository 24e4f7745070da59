#pragma once
// A scene's GUID names its scene channel (SPEC §3): equal content, equal GUID.
// It hashes the lights (every field, GUIDs included) and the geometry
// (positions and indices), not the file path, materials or cameras.
#include <cstdint>

#include "lightcuts/scene.h"
#include "lightcuts/guid.h"

namespace lc::client {

Guid compute_scene_guid(const Scene& scene);

// 64-bit FNV-1a over the meshes' positions and indices, in order.
uint64_t geometry_hash(const Scene& scene);

}  // namespace lc::client
