#pragma once
// A result tree's structure, checked on its links alone: each node's children,
// representative and subtree flags, copied out of the 140-byte nodes
// (LightTreeNode, static_assert in light_tree.h) into a compact array, so a
// 10^6-node channel is checked without reading its nodes again.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "lightcuts/result.h"
#include "lightcuts/tree/light_tree.h"

namespace lc {

struct NodeLinks {
    int32_t left;
    int32_t right;
    int32_t representative;
    // Indirect (the renderer clamps and skips whole subtrees by it) and patch
    // (radiosity patches, never clamped: kept apart from VPLs) hold per subtree.
    NodeFlags flags;
};

NodeLinks links_of(const LightTreeNode& node);

// The structure of a tree whose nodes each passed the per-node checks (child
// indices in range and after their parent): one parent each, `leaf_count`
// leaves, representatives that are leaves inside their subtree, and a
// cluster's indirect and patch flags set exactly when both children's are.
Status validate_links(std::span<const NodeLinks> links, uint32_t leaf_count);

// How error messages name node `index`.
std::string node_label(size_t index);

}  // namespace lc
