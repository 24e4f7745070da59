// Binary to 4-wide: breadth-first over the binary inner nodes that head a wide
// node, so a wide node's index is known when its parent names it.
#include "lightcuts/occlusion/wide_bvh.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

namespace lc {
namespace {

bool is_leaf(const GpuBvhNode& node) { return node.triangles != 0; }

// The binary node's children: left is next in pre-order, right is left's escape.
std::array<size_t, 2> children_of(const std::vector<GpuBvhNode>& binary, size_t inner) {
    const size_t left = inner + 1;
    return {left, static_cast<size_t>(binary[left].escape)};
}

// The slots of a wide node headed by binary node `head`: its children, each
// inner one replaced by its own two children. A leaf head is its only slot.
std::vector<size_t> wide_slots(const std::vector<GpuBvhNode>& binary, size_t head) {
    if (is_leaf(binary[head])) return {head};
    std::vector<size_t> slots;
    for (size_t child : children_of(binary, head)) {
        if (is_leaf(binary[child])) {
            slots.push_back(child);
        } else {
            for (size_t grandchild : children_of(binary, child)) slots.push_back(grandchild);
        }
    }
    return slots;
}

void set_slot_box(GpuWideBvhNode& node, int slot, const GpuBvhNode& box) {
    node.lo_x[slot] = box.bbox_min.x;
    node.lo_y[slot] = box.bbox_min.y;
    node.lo_z[slot] = box.bbox_min.z;
    node.hi_x[slot] = box.bbox_max.x;
    node.hi_y[slot] = box.bbox_max.y;
    node.hi_z[slot] = box.bbox_max.z;
}

// Nearest-first along the octant's diagonal: the slot whose box centre lies
// furthest against the direction first (ties: the lower slot). Unused slots last.
uint32_t octant_order(const GpuWideBvhNode& node, uint32_t used, uint32_t octant) {
    std::array<std::pair<double, uint32_t>, kBvhWidth> keyed{};
    for (uint32_t s = 0; s < kBvhWidth; ++s) {
        const double sx = (octant & 1u) ? -1.0 : 1.0;
        const double sy = (octant & 2u) ? -1.0 : 1.0;
        const double sz = (octant & 4u) ? -1.0 : 1.0;
        const int k = int(s);
        const double key = sx * (double(node.lo_x[k]) + double(node.hi_x[k])) +
                           sy * (double(node.lo_y[k]) + double(node.hi_y[k])) +
                           sz * (double(node.lo_z[k]) + double(node.hi_z[k]));
        keyed[s] = {key, s};
    }
    // Insertion sort of the used slots (std::sort's bounds confuse GCC's -Warray-bounds here).
    for (uint32_t i = 1; i < used; ++i)
        for (uint32_t j = i; j > 0 && keyed[j] < keyed[j - 1]; --j) std::swap(keyed[j], keyed[j - 1]);
    uint32_t order = 0;
    for (uint32_t k = 0; k < kBvhWidth; ++k) order |= keyed[k].second << (2 * k);
    return order;
}

void store_orders(GpuWideBvhNode& node, uint32_t used) {
    node.order = glm::uvec4(0u);
    for (uint32_t octant = 0; octant < 8; ++octant)
        node.order[int(octant / 4)] |= octant_order(node, used, octant) << (8 * (octant % 4));
}

// Bottom-up (children have larger indices): a node pushes its m hit slots and
// pops the first at once, so its subtree needs max(m, m - 1 + a child's need).
uint32_t stack_need(const std::vector<GpuWideBvhNode>& nodes) {
    std::vector<uint32_t> need(nodes.size(), 0);
    for (size_t i = nodes.size(); i-- > 0;) {
        uint32_t used = 0;
        uint32_t deepest_child = 0;
        for (int s = 0; s < int(kBvhWidth); ++s) {
            const uint32_t child = nodes[i].children[s];
            if (child == kBvhEmptyChild) continue;
            ++used;
            if ((child & kBvhLeafCountMask) == 0)
                deepest_child = std::max(deepest_child, need[child >> kBvhLeafCountBits]);
        }
        need[i] = std::max(used, used - 1 + deepest_child);
    }
    return need[0];
}

}  // namespace

WideBvh collapse_to_wide(const std::vector<GpuBvhNode>& binary) {
    WideBvh wide;
    if (binary.empty()) return wide;
    struct Pending {
        size_t head;     // binary node
        uint32_t depth;  // wide
    };
    std::vector<Pending> queue{{0, 0}};
    for (size_t next = 0; next < queue.size(); ++next) {
        const Pending pending = queue[next];
        const std::vector<size_t> slots = wide_slots(binary, pending.head);
        GpuWideBvhNode node;
        for (size_t s = 0; s < slots.size(); ++s) {
            const GpuBvhNode& child = binary[slots[s]];
            set_slot_box(node, int(s), child);
            if (is_leaf(child)) {
                node.children[int(s)] = child.triangles;
                ++wide.leaves;
                wide.depth = std::max(wide.depth, pending.depth + 1);
            } else {
                node.children[int(s)] = uint32_t(queue.size()) << kBvhLeafCountBits;
                queue.push_back({slots[s], pending.depth + 1});
            }
        }
        store_orders(node, uint32_t(slots.size()));
        wide.nodes.push_back(node);
    }
    wide.stack_need = stack_need(wide.nodes);
    return wide;
}

}  // namespace lc
