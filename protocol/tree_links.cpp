#include "protocol/tree_links.h"

#include <string>
#include <vector>

#include "protocol/channel_records.h"

namespace lc {
namespace {

// A cluster carries a subtree flag exactly when both its children do.
Status check_subtree_flag(size_t index, uint32_t flag, bool set, bool children) {
    if (set == children) return Ok{};
    const char* name = flag == kNodeIndirect ? "indirect" : "patch";
    return make_error(node_label(index) + ": " + name + " flag " + (set ? "set" : "clear") +
                      " but its children " + (children ? "both" : "do not both") + " carry it");
}

}  // namespace

std::string node_label(size_t index) { return "node " + std::to_string(index); }

NodeLinks links_of(const LightTreeNode& node) {
    return {node.left, node.right, node.representative, node.flags};
}

Status validate_links(std::span<const NodeLinks> links, uint32_t leaf_count) {
    const size_t n = links.size();
    if (n > kMaxTreeNodes) {
        return make_error("tree has " + std::to_string(n) + " nodes, above the limit of " +
                          std::to_string(kMaxTreeNodes));
    }
    // Child ranges (children after their parent) are validate_node's, already checked.
    std::vector<uint8_t> parents(n, 0);
    size_t leaves = 0;
    for (size_t i = 0; i < n; ++i) {
        const NodeLinks& node = links[i];
        if (node.left == kNoChild) {
            ++leaves;
            if (node.representative != static_cast<int32_t>(i)) {
                return make_error(node_label(i) + ": a leaf must represent itself, not node " +
                                  std::to_string(node.representative));
            }
            continue;
        }
        for (int32_t child : {node.left, node.right}) {
            if (++parents[static_cast<size_t>(child)] > 1) {
                return make_error(node_label(static_cast<size_t>(child)) + " has more than one parent");
            }
        }
        // The renderer clamps and skips by the indirect flag, and leaves patches
        // unclamped: each must hold for every light below.
        const NodeLinks& left = links[static_cast<size_t>(node.left)];
        const NodeLinks& right = links[static_cast<size_t>(node.right)];
        for (uint32_t flag : {kNodeIndirect, kNodePatch}) {
            const bool both = (left.flags.bits & right.flags.bits & flag) != 0;
            if (Status s = check_subtree_flag(i, flag, (node.flags.bits & flag) != 0, both); !s) return s;
        }
    }
    // Children always follow their parent, so a node without a parent other
    // than the root would start a second tree.
    for (size_t i = 1; i < n; ++i) {
        if (parents[i] == 0) return make_error(node_label(i) + " has no parent");
    }
    if (leaves != leaf_count) {
        return make_error("tree says it has " + std::to_string(leaf_count) + " leaves, its nodes hold " +
                          std::to_string(leaves));
    }
    if (n == 0) return Ok{};

    // Pre-order numbering without a stack (chains can be 10^6 deep): subtree
    // sizes bottom-up (children have larger indices than their parent), then
    // each child's entry from its parent's, top-down. Node j lies in i's
    // subtree exactly when enter[i] <= enter[j] < enter[i] + subtree[i]; a
    // subtree of one node is a leaf.
    std::vector<uint32_t> subtree(n, 1);
    for (size_t k = n; k-- > 0;) {
        if (links[k].left == kNoChild) continue;
        subtree[k] =
            1 + subtree[static_cast<size_t>(links[k].left)] + subtree[static_cast<size_t>(links[k].right)];
    }
    std::vector<uint32_t> enter(n, 0);
    for (size_t i = 0; i < n; ++i) {
        if (links[i].left == kNoChild) continue;
        const auto left = static_cast<size_t>(links[i].left);
        enter[left] = enter[i] + 1;
        enter[static_cast<size_t>(links[i].right)] = enter[i] + 1 + subtree[left];
    }
    for (size_t i = 0; i < n; ++i) {
        const auto rep = static_cast<size_t>(links[i].representative);
        if (subtree[rep] != 1) {
            return make_error(node_label(i) + ": representative " + std::to_string(rep) + " is not a leaf");
        }
        if (enter[rep] < enter[i] || enter[rep] >= enter[i] + subtree[i]) {
            return make_error(node_label(i) + ": representative " + std::to_string(rep) +
                              " is outside its subtree");
        }
    }
    return Ok{};
}

}  // namespace lc
