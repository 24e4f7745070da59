#pragma once
// The full-precision light tree the builders share while building. Every
// attribute is double; lightcuts/tree/tree_export.h turns it into the float
// lc::LightTree in one place, with conservative rounding.
#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "lightcuts/guid.h"
#include "lightcuts/scene_light.h"
#include "lightcuts/tree/node_flags.h"

namespace lc {

struct BuildNode {
    Guid guid;
    int32_t left = kNoChild;  // arena indices; a leaf has neither child
    int32_t right = kNoChild;
    // Arena index of the leaf whose light represents this node (leaves: itself).
    uint32_t representative = 0;
    // Smallest input light index in the subtree: orders levels and children.
    uint32_t min_light_index = 0;
    LightType type = LightType::kPoint;
    // A junction of per-type trees (always refined); every light below
    // indirect, or a radiosity patch: the builders never join indirect and
    // direct lights, nor patches and VPLs, below a junction.
    NodeFlags flags;

    glm::dvec3 intensity{0.0};  // RGB sum of the leaves' color * intensity
    double brightness = 0.0;    // sum of the leaves' scalar intensity
    double radius = kUnboundedRadius;
    // Bounds of the leaves' positions (directions, as unit-sphere points, for
    // directional lights).
    glm::dvec3 bbox_min{0.0};
    glm::dvec3 bbox_max{0.0};
    // Orientation cone containing every leaf's direction; cos = -1: all directions.
    glm::dvec3 cone_axis{0.0, 0.0, -1.0};
    double cone_cos = -1.0;

    bool is_leaf() const { return left == kNoChild && right == kNoChild; }
    bool unbounded() const { return radius < 0.0; }
};

// Asks the cache for every line of a node ahead of its use: merges and the
// export read all of it, and its 160 bytes span three cache lines.
inline void prefetch_build_node(const BuildNode& node) {
    const char* bytes = reinterpret_cast<const char*>(&node);
    __builtin_prefetch(bytes);
    __builtin_prefetch(bytes + 64);
    __builtin_prefetch(bytes + 128);
    __builtin_prefetch(bytes + sizeof(BuildNode) - 1);
}

// The same for a light (76 bytes: up to two cache lines), which a leaf is made from.
inline void prefetch_light(const SceneLight& light) {
    const char* bytes = reinterpret_cast<const char*>(&light);
    __builtin_prefetch(bytes);
    __builtin_prefetch(bytes + sizeof(SceneLight) - 1);
}

// The arena's allocator: resize() leaves the new nodes unwritten (BuildNode is
// an aggregate, trivially destructible). The builders size the arena for a
// step and then fill every new node on several threads; writing a default
// node first would touch 10^6 fresh pages on one thread only to overwrite them.
template <class T>
struct UnwrittenOnResize : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UnwrittenOnResize<U>;
    };
    UnwrittenOnResize() = default;
    template <class U>
    UnwrittenOnResize(const UnwrittenOnResize<U>&) noexcept {}

    template <class U>
    void construct(U*) noexcept {}
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        std::construct_at(p, std::forward<Args>(args)...);
    }
};

// A leaf for input light `light_index` (SPEC §4 leaf rules).
BuildNode make_leaf(const SceneLight& light, uint32_t light_index);

// Nodes of one build. Leaves come first, one per input light in input order, so
// leaf arena index == input light index; clusters are appended after them.
// A leaf is made afresh from its light whenever it is read (node()): merges
// and the export read 10^6 leaves at random, and a light is half a leaf
// node's bytes. So the server's builds leave the leaves' slots in `nodes`
// unwritten (tests may fill them with make_leaf): read a node that may be a
// leaf only through node(), representative_of() and min_light_index_of().
struct BuildArena {
    std::span<const SceneLight> lights;
    // resize() leaves new nodes unwritten: whoever grows it fills them.
    std::vector<BuildNode, UnwrittenOnResize<BuildNode>> nodes;

    bool is_leaf_index(uint32_t index) const { return index < lights.size(); }

    BuildNode node(uint32_t index) const {
        return is_leaf_index(index) ? make_leaf(lights[index], index) : nodes[index];
    }
    uint32_t representative_of(uint32_t index) const {
        return is_leaf_index(index) ? index : nodes[index].representative;
    }
    uint32_t min_light_index_of(uint32_t index) const {
        return is_leaf_index(index) ? index : nodes[index].min_light_index;
    }

    const SceneLight& representative_light(const BuildNode& node) const {
        return lights[node.representative];
    }
};

// Progress of one per-type build as a fraction in [0, 1]; false cancels it.
using BuildProgressFn = std::function<bool(double fraction)>;


}  // namespace lc
