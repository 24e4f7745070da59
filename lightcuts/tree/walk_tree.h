#pragma once
// The light tree as every walk reads it, on the GPU and on the CPU (pbrt-v4
// walks one compact node on both): the compact nodes (GpuTreeNode, 64 bytes,
// compact_node.h) in the tree's breadth-first order with pre-order links, and
// the leaves' lights, through which a node is evaluated as a cluster. Made
// from the import form (LightTree) once, by make_walk_tree (gpu_layout.h),
// which checks the links, so a walk needs no bounds checks in release builds
// (debug builds check every access: LC_DCHECK_INDEX).
#include <cstdint>
#include <vector>

#include "lightcuts/check.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/scene_light.h"

namespace lc {

struct WalkTree {
    // nodes[0] is the root when the tree is not empty; every child index is
    // greater than its parent's (the import form's indices, kept).
    std::vector<GpuTreeNode> nodes;
    // The leaves in node-index order: the nodes' representatives point here.
    std::vector<GpuLight> leaves;
    uint32_t depth = 0;  // longest root-to-leaf path, in edges

    bool empty() const { return nodes.empty(); }
    const GpuTreeNode& node(int32_t index) const {
        LC_DCHECK_INDEX(index, nodes.size());
        return nodes[size_t(index)];
    }
    // The light that evaluates node `index` as a cluster (a leaf's own).
    const GpuLight& light_of(int32_t index) const {
        const uint32_t representative = node(index).representative;
        LC_DCHECK_INDEX(representative, leaves.size());
        return leaves[representative];
    }
};

inline LightType node_type(const GpuTreeNode& node) {
    return LightType(node.flags >> kNodeTypeShift);
}
inline bool is_leaf(const GpuTreeNode& node) {
    return node.first_child == kNoChild;
}
inline bool joins_types(const GpuTreeNode& node) {
    return (node.flags & kNodeMixedTypes) != 0;
}
inline bool is_indirect(const GpuTreeNode& node) {
    return (node.flags & kNodeIndirect) != 0;
}
inline bool is_patch(const GpuTreeNode& node) {
    return (node.flags & kNodePatch) != 0;
}
inline bool is_indirect(const GpuLight& light) {
    return (light.flags & kGpuLightIndirect) != 0;
}
inline bool is_patch(const GpuLight& light) {
    return (light.flags & kGpuLightPatch) != 0;
}

// The children of node `index` (left before right, as the import form had
// them), from the pre-order links: the first child, and its escape when that
// is still inside the node's subtree. Writes them to `out`, returns how many.
inline int children_of(const WalkTree& tree, int32_t index, int32_t out[2]) {
    const GpuTreeNode& node = tree.node(index);
    if (node.first_child == kNoChild) return 0;
    out[0] = node.first_child;
    const int32_t next = tree.node(node.first_child).escape;
    if (next == node.escape) return 1;
    out[1] = next;
    return 2;
}

}  // namespace lc
