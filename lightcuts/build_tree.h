#pragma once
// The full-precision light tree the builders share while building. Every
// attribute is double; lightcuts/tree_export.h turns it into the float
// lc::LightTree in one place, with conservative rounding.
#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "lightcuts/guid.h"
#include "lightcuts/scene_light.h"

namespace lc {

inline constexpr int32_t kNoBuildChild = -1;
// Influence radius of a node that reaches everywhere (no range, directional, or
// a child that is unbounded).
inline constexpr double kUnboundedBuildRadius = -1.0;

struct BuildNode {
    Guid guid;
    int32_t left = kNoBuildChild;  // arena indices; a leaf has neither child
    int32_t right = kNoBuildChild;
    // Arena index of the leaf whose light represents this node (leaves: itself).
    uint32_t representative = 0;
    // Smallest input light index in the subtree: orders levels and children.
    uint32_t min_light_index = 0;
    LightType type = LightType::kPoint;
    bool mixed_types = false;  // junction of per-type trees, always refined
    // Every light under the node is indirect (SceneLight::indirect): the
    // builders never join indirect and direct lights below a junction.
    bool indirect = false;
    // Every light under the node is a radiosity patch (SceneLight::patch); the
    // builders never join patches and VPLs below a junction either.
    bool patch = false;

    glm::dvec3 intensity{0.0};  // RGB sum of the leaves' color * intensity
    double brightness = 0.0;    // sum of the leaves' scalar intensity
    double radius = kUnboundedBuildRadius;
    // Bounds of the leaves' positions (directions, as unit-sphere points, for
    // directional lights).
    glm::dvec3 bbox_min{0.0};
    glm::dvec3 bbox_max{0.0};
    // Orientation cone containing every leaf's direction; cos = -1: all directions.
    glm::dvec3 cone_axis{0.0, 0.0, -1.0};
    double cone_cos = -1.0;

    bool is_leaf() const { return left == kNoBuildChild && right == kNoBuildChild; }
    bool unbounded() const { return radius < 0.0; }
};

// Nodes of one build. Leaves come first, one per input light in input order, so
// leaf arena index == input light index; clusters are appended after them.
struct BuildArena {
    std::span<const SceneLight> lights;
    std::vector<BuildNode> nodes;

    const SceneLight& representative_light(const BuildNode& node) const {
        return lights[node.representative];
    }
};

// Progress of one per-type build as a fraction in [0, 1]; false cancels it.
using BuildProgressFn = std::function<bool(double fraction)>;


}  // namespace lc
