#pragma once
// The real-time mode's light-draw records (GpuDrawPair, gpu_structs.h): per
// tree node, what its two children weigh in the draw and where each leads, so
// the shader's descent reads one record a level.
#include <span>
#include <vector>

#include "lightcuts/device/gpu_structs.h"

namespace lc {

// One record per node of `nodes` (compact pre-order nodes, make_walk_tree):
// a leaf's record is unused; an internal node's holds its children's bounding
// spheres (radius -1 for a directional or mixed-type child, weighed by
// intensity alone), scalar intensities and destinations (a node index, or
// ~representative for a leaf child). A node with one child gets intensity1 0
// and child1 = child0. Never empty: an empty tree gets one unused record (a
// storage buffer cannot be empty).
std::vector<GpuDrawPair> make_draw_pairs(std::span<const GpuTreeNode> nodes);

}  // namespace lc
