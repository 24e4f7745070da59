#include "lightmass_server/builders/cluster_attributes.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "lightcuts/seeded_mixer.h"

namespace lc::bake {
namespace {

constexpr double kPi = std::numbers::pi;

glm::dvec3 to_dvec3(const glm::vec3& v) {
    return glm::dvec3(v.x, v.y, v.z);
}

// A unit vector perpendicular to `v` (v is unit length).
glm::dvec3 any_perpendicular(const glm::dvec3& v) {
    const glm::dvec3 helper =
        std::abs(v.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    return glm::normalize(glm::cross(v, helper));
}

uint64_t mix_guid(uint64_t h, const Guid& g) {
    h = mix64(h ^ ((uint64_t(g.a) << 32) | g.b));
    return mix64(h ^ ((uint64_t(g.c) << 32) | g.d));
}

// Uniform in [0, 1) from (seed, first GUID, second GUID).
double counter_uniform(uint64_t seed, const Guid& first, const Guid& second) {
    uint64_t h = mix64(seed ^ kGoldenGamma);
    h = mix_guid(h, first);
    h = mix_guid(h, second);
    return unit_interval(h);
}

// Sums and bounds every cluster kind shares.
BuildNode combine_sums_and_bounds(const BuildNode& left, const BuildNode& right) {
    BuildNode node;
    node.guid = Guid::combine(left.guid, right.guid);
    node.min_light_index = std::min(left.min_light_index, right.min_light_index);
    node.intensity = left.intensity + right.intensity;
    node.brightness = left.brightness + right.brightness;
    node.bbox_min = glm::min(left.bbox_min, right.bbox_min);
    node.bbox_max = glm::max(left.bbox_max, right.bbox_max);
    node.flags.set(kNodeIndirect, left.flags.indirect() && right.flags.indirect());
    node.flags.set(kNodePatch, left.flags.patch() && right.flags.patch());
    return node;
}

// Arena nodes a and b as a cluster's children: the first holds the smaller
// input light index.
struct Children {
    BuildNode node_a, node_b;
    bool a_first;
    uint32_t left_index, right_index;

    Children(const BuildArena& arena, uint32_t a, uint32_t b)
        : node_a(arena.node(a)), node_b(arena.node(b)) {
        a_first = !(node_b.min_light_index < node_a.min_light_index);
        left_index = a_first ? a : b;
        right_index = a_first ? b : a;
    }
    const BuildNode& left() const { return a_first ? node_a : node_b; }
    const BuildNode& right() const { return a_first ? node_b : node_a; }
};

}  // namespace

double angle_between(const glm::dvec3& u, const glm::dvec3& v) {
    // 2 atan2(|u - v|, |u + v|) keeps full precision near 0 and pi.
    return 2.0 * std::atan2(glm::length(u - v), glm::length(u + v));
}

OrientationCone cone_union(const OrientationCone& a, const OrientationCone& b) {
    if (a.is_full() || b.is_full()) return OrientationCone{};
    const double theta_a = std::acos(std::clamp(a.cos_theta, -1.0, 1.0));
    const double theta_b = std::acos(std::clamp(b.cos_theta, -1.0, 1.0));
    const double theta_d = angle_between(a.axis, b.axis);
    // One cone already holds the other.
    if (std::min(theta_d + theta_b, kPi) <= theta_a) return a;
    if (std::min(theta_d + theta_a, kPi) <= theta_b) return b;

    // Half-angle of the cone spanning both: from a's far edge to b's far edge.
    const double theta_o = 0.5 * (theta_a + theta_d + theta_b);
    if (theta_o >= kPi) return OrientationCone{};

    // Rotate a's axis towards b's by theta_r within the plane of both axes.
    const double theta_r = theta_o - theta_a;
    glm::dvec3 towards_b = b.axis - a.axis * glm::dot(a.axis, b.axis);
    const double towards_length = glm::length(towards_b);
    towards_b = towards_length > 1e-12 ? towards_b / towards_length : any_perpendicular(a.axis);
    const glm::dvec3 axis =
        glm::normalize(a.axis * std::cos(theta_r) + towards_b * std::sin(theta_r));
    return OrientationCone{axis, std::cos(theta_o)};
}

bool representative_from_first(const BuildNode& first, const BuildNode& second,
                               RepresentativeRule rule, uint64_t seed) {
    if (rule == RepresentativeRule::kThesisFirst) return true;
    const double I_first = scalar_intensity(first);
    const double I_sum = I_first + scalar_intensity(second);
    // Zero (or overflowing) total intensity: no meaningful probability, keep the first.
    if (!(I_sum > 0.0) || !std::isfinite(I_sum)) return true;
    return counter_uniform(seed, first.guid, second.guid) * I_sum < I_first;
}

BuildNode merge_clusters(const BuildArena& arena, uint32_t a, uint32_t b, RepresentativeRule rule,
                         uint64_t seed) {
    const Children children(arena, a, b);
    const BuildNode& left = children.left();
    const BuildNode& right = children.right();

    BuildNode node = combine_sums_and_bounds(left, right);
    node.left = int32_t(children.left_index);
    node.right = int32_t(children.right_index);
    node.type = left.type;
    node.representative = representative_from_first(left, right, rule, seed) ? left.representative
                                                                             : right.representative;

    const OrientationCone cone =
        cone_union({left.cone_axis, left.cone_cos}, {right.cone_axis, right.cone_cos});
    node.cone_axis = cone.axis;
    node.cone_cos = cone.cos_theta;

    // Thesis rule: the sphere around the representative's position that holds
    // both children's influence spheres.
    if (left.unbounded() || right.unbounded()) {
        node.radius = kUnboundedRadius;
    } else {
        const glm::dvec3 p = to_dvec3(arena.lights[node.representative].position);
        const double r_left =
            glm::length(p - to_dvec3(arena.lights[left.representative].position)) + left.radius;
        const double r_right =
            glm::length(p - to_dvec3(arena.lights[right.representative].position)) + right.radius;
        node.radius = std::max(r_left, r_right);
    }
    return node;
}

BuildNode make_junction(const BuildArena& arena, uint32_t a, uint32_t b) {
    const Children children(arena, a, b);
    const BuildNode& left = children.left();
    const BuildNode& right = children.right();

    BuildNode node = combine_sums_and_bounds(left, right);
    node.left = int32_t(children.left_index);
    node.right = int32_t(children.right_index);
    node.type = left.type;
    node.flags.set(kNodeMixedTypes, true);
    node.representative = left.representative;
    node.radius = kUnboundedRadius;
    node.cone_axis = glm::dvec3(0.0, 0.0, -1.0);
    node.cone_cos = -1.0;
    return node;
}

glm::dvec3 light_point(const SceneLight& light) {
    return light.type == LightType::kDirectional ? to_dvec3(light.direction)
                                                 : to_dvec3(light.position);
}

}  // namespace lc::bake
