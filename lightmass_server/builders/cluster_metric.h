#pragma once
// The paper's cluster size metric (section 4, "Similarity Metric"):
//   I_C * (alpha_C^2 + c^2 (1 - cos beta_C)^2)
// alpha_C: diagonal of the merged bounding box; beta_C: half-angle of the
// merged orientation cone; c: scene diagonal for oriented (spot and oriented) lights, 0 for
// omni and directional lights. Also a lower bound of it over a whole group of
// clusters, so a spatial hierarchy can prune its nearest-neighbour search.
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "lightmass_server/builders/cluster_attributes.h"

namespace lc::bake {

// What the metric needs of a cluster, packed for cache-friendly searches.
struct ClusterShape {
    glm::dvec3 lo{0.0};
    glm::dvec3 hi{0.0};
    double I = 0.0;  // scalar intensity (sum of RGB)
};

struct ClusterCone {
    glm::dvec3 axis{0.0, 0.0, -1.0};
    double cos_theta = -1.0;
    double theta = std::numbers::pi;  // acos(cos_theta), cached
};

struct MetricParams {
    double c2 = 0.0;  // c^2; 0 disables the orientation term
    // Added to I_C so that dark (zero-intensity) clusters still cluster by
    // size instead of all tying at 0; 1e-15 of the mean leaf intensity.
    double intensity_floor = 1.0;
    bool oriented() const { return c2 > 0.0; }
};

// The clusters of one agglomerative build: index = local cluster id.
struct ClusterSet {
    MetricParams params;
    std::vector<ClusterShape> shapes;
    std::vector<ClusterCone> cones;  // filled only when params.oriented()
};

inline double squared_diagonal(const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 d = hi - lo;
    return glm::dot(d, d);
}

inline ClusterCone make_cluster_cone(const glm::dvec3& axis, double cos_theta) {
    return ClusterCone{axis, cos_theta, std::acos(std::clamp(cos_theta, -1.0, 1.0))};
}

// I_C (alpha_C^2 + c^2 (1 - cos beta_C)^2) for merging clusters A and B; the
// cones are read only when the metric is oriented.
inline double cluster_metric(const MetricParams& params, const ClusterShape& A,
                             const ClusterShape& B, const ClusterCone& cone_A,
                             const ClusterCone& cone_B) {
    const double I_C = A.I + B.I + params.intensity_floor;
    const double alpha2 = squared_diagonal(glm::min(A.lo, B.lo), glm::max(A.hi, B.hi));
    if (!params.oriented()) return I_C * alpha2;
    const OrientationCone cone =
        cone_union({cone_A.axis, cone_A.cos_theta}, {cone_B.axis, cone_B.cos_theta});
    const double one_minus_cos = 1.0 - cone.cos_theta;
    return I_C * (alpha2 + params.c2 * one_minus_cos * one_minus_cos);
}

inline double cluster_metric(const ClusterSet& set, uint32_t a, uint32_t b) {
    if (!set.params.oriented()) {
        static const ClusterCone kUnused;
        return cluster_metric(set.params, set.shapes[a], set.shapes[b], kUnused, kUnused);
    }
    return cluster_metric(set.params, set.shapes[a], set.shapes[b], set.cones[a], set.cones[b]);
}

// Bounds of a group of clusters, for the lower bound below.
struct GroupBounds {
    glm::dvec3 lo{0.0};  // min over members of their lo
    glm::dvec3 hi{0.0};  // max over members of their hi
    double min_I = 0.0;
    // Oriented only: a cone holding every member's axis, and the smallest
    // member half-angle.
    glm::dvec3 axis{0.0, 0.0, -1.0};
    double spread = std::numbers::pi;
    double min_theta = 0.0;
};

// A lower bound of cluster_metric(a, m) over every member m of the group.
// Per axis the merged extent is at least a's own, and at least the gap from
// a's far side to the group's near side; beta_C >= max(theta_a, theta_m,
// (theta_a + angle(axes) + theta_m) / 2) with the axis angle at least
// angle(a, group axis) - spread.
inline double cluster_metric_lower_bound(const ClusterSet& set, uint32_t a,
                                         const GroupBounds& group) {
    const ClusterShape& A = set.shapes[a];
    const double I_C = A.I + group.min_I + set.params.intensity_floor;
    const glm::dvec3 extent = glm::max(A.hi - A.lo, glm::max(group.lo - A.lo, A.hi - group.hi));
    const double alpha2 = glm::dot(extent, extent);
    if (!set.params.oriented()) return I_C * alpha2;
    const ClusterCone& cone = set.cones[a];
    const double axis_gap = std::max(0.0, angle_between(cone.axis, group.axis) - group.spread);
    const double beta = std::min(
        std::numbers::pi,
        std::max({cone.theta, group.min_theta, 0.5 * (cone.theta + axis_gap + group.min_theta)}));
    const double one_minus_cos = 1.0 - std::cos(beta);
    // The angle terms are not monotone under rounding: shave a relative 1e-9.
    return I_C * (alpha2 + set.params.c2 * one_minus_cos * one_minus_cos) * (1.0 - 1e-9);
}

}  // namespace lc::bake
