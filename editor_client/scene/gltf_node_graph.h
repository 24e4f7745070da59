#pragma once
// The glTF node graph as the loader walks it: checked to be disjoint strict
// trees (on every node, without recursion), the roots of the scene drawn,
// and each node's local transform (matrix, or translation * rotation *
// scale), every number checked.
#include <glm/mat4x4.hpp>

#include <vector>

#include "editor_client/scene/gltf_diagnostics.h"
#include "editor_client/scene/gltf_node_table.h"
#include "lightcuts/result.h"

namespace lc::client {

// Children exist, no node is its own child, has two parents or is its own ancestor.
Status validate_gltf_node_graph(const GltfNodeTable& table, const GltfDiagnostics& diagnostics);

// The roots of the scene `default_scene` names (-1: none), else of scenes[0],
// else every root node (with a warning: the spec leaves this open).
Result<std::vector<int>> gltf_scene_roots(const GltfNodeTable& table, int default_scene,
                                          GltfDiagnostics& diagnostics);

// Node `node_index`'s transform relative to its parent.
Result<glm::dmat4> gltf_local_transform(const GltfNodeTable& table, int node_index,
                                        const GltfDiagnostics& diagnostics);

}  // namespace lc::client
