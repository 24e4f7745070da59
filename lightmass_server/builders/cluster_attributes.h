#pragma once
// Leaf and cluster attributes (SPEC §4, the paper's section 4): intensity sums
// in double, the representative rule, bounding box, orientation cone and the
// thesis's influence radius.
#include <glm/vec3.hpp>

#include <cstdint>

#include "lightcuts/tree/build_tree.h"
#include "protocol/messages.h"

namespace lc::bake {

// A cone of directions: every direction within acos(cos_theta) of `axis`.
// cos_theta == -1 holds all directions.
struct OrientationCone {
    glm::dvec3 axis{0.0, 0.0, -1.0};
    double cos_theta = -1.0;

    bool is_full() const { return cos_theta <= -1.0; }
};

// The smallest cone around the great-circle arc between the two axes that
// contains both cones (pbrt's DirectionCone union); conservative, never NaN.
OrientationCone cone_union(const OrientationCone& a, const OrientationCone& b);

// Angle in [0, pi] between two unit vectors, accurate also for tiny and
// near-pi angles (atan2 form instead of acos of a dot product).
double angle_between(const glm::dvec3& u, const glm::dvec3& v);

// Scalar intensity used by the representative rule and the cluster metric:
// the sum of the RGB components.
inline double scalar_intensity(const BuildNode& node) {
    return node.intensity.x + node.intensity.y + node.intensity.z;
}

// Which child's representative the cluster takes; `first` is the child whose
// subtree holds the smaller input light index. kIntensity draws with
// probability I_first / (I_first + I_second) from a counter-based hash of
// (seed, both GUIDs), so the choice does not depend on evaluation order.
bool representative_from_first(const BuildNode& first, const BuildNode& second,
                               RepresentativeRule rule, uint64_t seed);

// The cluster of arena nodes `a` and `b` (either order: the child with the
// smaller input light index becomes the left child). Not yet in the arena.
BuildNode merge_clusters(const BuildArena& arena, uint32_t a, uint32_t b, RepresentativeRule rule,
                         uint64_t seed);

// Asks the cache for the lights that merging arena nodes a and b reads (their
// representatives'), once the nodes themselves are cached: the lights sit at
// random in the input, far from the nodes.
inline void prefetch_representative_lights(const BuildArena& arena, uint32_t a, uint32_t b) {
    for (const uint32_t child : {a, b}) {
        // A leaf represents itself; a cluster's node says who represents it.
        prefetch_light(arena.lights[arena.representative_of(child)]);
    }
}

// Asks the cache for what merging reads of arena node `index`: a leaf's
// light, or a cluster's node.
inline void prefetch_merge_input(const BuildArena& arena, uint32_t index) {
    if (arena.is_leaf_index(index)) {
        prefetch_light(arena.lights[index]);
    } else {
        prefetch_build_node(arena.nodes[index]);
    }
}

// A node that joins two trees of different light types: sums and bounds as a
// cluster, but unbounded, all directions, and flagged kNodeMixedTypes so the
// renderer always refines it.
BuildNode make_junction(const BuildArena& arena, uint32_t a, uint32_t b);

// The point a light is paired or clustered by: its position, or its direction
// for directional lights (a point on the unit sphere).
glm::dvec3 light_point(const SceneLight& light);

}  // namespace lc::bake
