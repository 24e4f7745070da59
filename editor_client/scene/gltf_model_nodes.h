#pragma once
// The slow path's node table: tinygltf's nodes, scenes and punctual lights
// copied into the flat GltfNodeTable the simdjson reader fills on the fast
// path (gltf_node_reader.h), so the loader reads both the same way.
#include <tiny_gltf.h>

#include "editor_client/scene/gltf_node_table.h"

namespace lc::client {

GltfNodeTable node_table_from(const tinygltf::Model& model);

}  // namespace lc::client
