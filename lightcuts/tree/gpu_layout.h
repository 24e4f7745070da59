#pragma once
// The one place that converts scene lights and tree nodes into the structs the
// shaders (and the CPU evaluator's walks) read (lightcuts/device/gpu_structs.h, shared with the GLSL).
#include <cstdint>
#include <vector>

#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/tree/light_tree.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc {

// A scene light (glTF units) as the shader evaluates it.
GpuLight make_gpu_light(const SceneLight& light);
// A leaf of the tree as the shader evaluates it: its light's parameters and RGB
// intensity (clusters are shaded through their representative leaf).
GpuLight make_gpu_leaf_light(const LightTreeNode& node);

// Pre-order escape index of every node, computed iteratively in one pass over
// the breadth-first order (a parent always precedes its children). Fails on a
// child index that is out of range, not greater than its parent's, or shared.
Result<std::vector<int32_t>> derive_escape_indices(const LightTree& tree);

// The tree as the GPU and the CPU evaluator walk it (walk_tree.h): the one
// conversion from the import form. Fails on malformed links, non-finite
// values, or a representative that is not a leaf.
Result<WalkTree> make_walk_tree(const LightTree& tree);

}  // namespace lc
