#pragma once
// The one place that converts scene lights and tree nodes into the structs the
// shaders read (lightcuts/device/gpu_structs.h, shared with the GLSL).
#include <cstdint>
#include <vector>

#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/light_tree.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"

namespace lc {

// A scene light (glTF units) as the shader evaluates it.
GpuLight make_gpu_light(const SceneLight& light);
// A tree node evaluated as a cluster: its representative's parameters with
// the cluster's RGB intensity.
GpuLight make_gpu_cluster_light(const LightTreeNode& node);

// Pre-order escape index of every node, computed iteratively in one pass over
// the breadth-first order (a parent always precedes its children). Fails on a
// child index that is out of range, not greater than its parent's, or shared.
Result<std::vector<int32_t>> derive_escape_indices(const LightTree& tree);

// Everything the GPU reads about a tree.
struct GpuTree {
    std::vector<GpuTreeNode> nodes;
    std::vector<GpuLight> leaves;  // the tree's leaves in index order (reference mode)
    uint32_t depth = 0;            // longest root-to-leaf path, in edges
};

Result<GpuTree> make_gpu_tree(const LightTree& tree);
std::vector<GpuNodeBounds> make_gpu_node_bounds(const LightTree& tree);

}  // namespace lc
