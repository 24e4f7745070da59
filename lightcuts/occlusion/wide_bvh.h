#pragma once
// The 4-wide layout of the occluder BVH that shadow rays walk: each binary
// inner node with its children's children (or its leaf children) becomes one
// GpuWideBvhNode, so a step tests up to four boxes and a wide level spans two
// binary ones (the wide depth is at most half the binary depth, rounded up).
// Each node keeps, per octant of the ray's direction, its slots in
// nearest-first order, and the build reports the stack the walk needs.
#include <cstdint>
#include <vector>

#include "lightcuts/device/gpu_structs.h"

namespace lc {

struct WideBvh {
    std::vector<GpuWideBvhNode> nodes;  // node 0 is the root; children after parents
    uint32_t leaves = 0;                // leaf slots in all
    uint32_t depth = 0;                 // longest root-to-leaf path, in wide edges
    // Most entries the walk's stack holds at once, whatever the rays (every
    // slot's box hit, nearest-first in any order).
    uint32_t stack_need = 0;
};

// From the binary pre-order layout with escapes (ShadowBvh::gpu_nodes); empty
// when it is. Deterministic: a function of the binary nodes alone.
WideBvh collapse_to_wide(const std::vector<GpuBvhNode>& binary);

// The octant of a direction as GpuWideBvhNode::order indexes it.
inline uint32_t direction_octant(bool x_negative, bool y_negative, bool z_negative) {
    return uint32_t(x_negative) | uint32_t(y_negative) << 1 | uint32_t(z_negative) << 2;
}

// The slots of `node` nearest-first for `octant`: slot k is (order >> 2k) & 3.
inline uint32_t slot_order(const GpuWideBvhNode& node, uint32_t octant) {
    return (node.order[int(octant / 4)] >> (8 * (octant % 4))) & 0xffu;
}

}  // namespace lc
