// The CPU evaluator in double precision: the ground truth the shaders are
// tested against. Every formula is shading_model.h's, evaluated the same way.
//
// Conventions the GPU mirrors:
// - A shading point exactly on a light (d = 0) gets nothing from it: the
//   direction to the light is undefined.
// - Radius criterion: a node is refined while |p - position| < radius
//   (strictly; radius < 0 means unbounded, always inside), or when it is a
//   mixed_types junction.
// - Bound criterion: colours are compared through their largest channel:
//   a node is refined while max_c(bound_c) > error_ratio * max_c(total_c).
#include "lightcuts/cpu_evaluator.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "lightcuts/bound_walk.h"
#include "lightcuts/compact_node.h"
#include "lightcuts/material_model.h"
#include "lightcuts/shading_model.h"
#include "lightcuts/shadow_bvh.h"
#include "lightcuts/shadow_ray.h"

namespace lc {
namespace {

// What shading needs from a light or from a node's representative.
struct Emitter {
    LightType type = LightType::kPoint;
    glm::dvec3 position{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0};
    double range = 0.0;
    double cos_inner = 1.0;
    double cos_outer = 0.0;
};

Emitter emitter_of(const SceneLight& light) {
    Emitter e;
    e.type = light.type;
    e.position = glm::dvec3(light.position);
    e.direction = glm::dvec3(light.direction);
    e.range = light.range;
    e.cos_inner = std::cos(double(light.inner_cone_angle));
    e.cos_outer = std::cos(double(light.outer_cone_angle));
    return e;
}

Emitter emitter_of(const LightTreeNode& node) {
    Emitter e;
    e.type = node.type;
    e.position = glm::dvec3(node.position);
    e.direction = glm::dvec3(node.direction);
    e.range = node.range;
    e.cos_inner = node.spot_cos_inner;
    e.cos_outer = node.spot_cos_outer;
    return e;
}

bool has_lobe(const SurfacePoint& p) { return shading::has_lobe(p.specular, p.exponent); }

glm::dvec3 diffuse_term(const SurfacePoint& p) {
    return {shading::lambert(p.albedo.x), shading::lambert(p.albedo.y),
            shading::lambert(p.albedo.z)};
}

// Outgoing radiance per unit RGB intensity: f_r * G (shading_model.h).
glm::dvec3 unit_response(const Emitter& e, const SurfacePoint& p) {
    double G = 0.0;
    glm::dvec3 l = -e.direction;
    if (e.type == LightType::kDirectional) {
        G = std::max(glm::dot(p.normal, l), 0.0);
        // Stored directions are unit to float precision; a sharp lobe notices.
        const double len = glm::length(l);
        if (len > 0.0) l /= len;
    } else {
        const glm::dvec3 L = e.position - p.position;
        const double d2 = glm::dot(L, L);
        if (!(d2 > 0.0)) return glm::dvec3(0.0);
        const double d = std::sqrt(d2);
        l = L / d;
        const double cos_theta = glm::dot(p.normal, L) / d;
        if (!(cos_theta > 0.0)) return glm::dvec3(0.0);
        G = shading::range_window(d, e.range) * cos_theta * shading::inverse_square(d2);
        if (e.type == LightType::kSpot) {
            const double cos_s = glm::dot(-L / d, e.direction);
            G *= shading::spot_attenuation(cos_s, e.cos_inner, e.cos_outer);
        }
    }
    if (G > 0.0 && p.occluders != nullptr)
        G *= light_visibility(*p.occluders, p.shadow_bias, e.type, e.position, e.direction,
                              p.position, p.normal);
    return material_response(p, l) * G;
}

double max_channel(const glm::dvec3& v) {
    return std::max({v.x, v.y, v.z});
}

// Upper bound of cos(angle(axis, v)) over every vector v in the box [lo, hi]
// (paper Eq. 4): rotate the box into a frame whose z is `axis`, take the
// rotated box's bounding box (centre rotated, half extents through |R|: the
// eight rotated corners' box), then bound v_z / |v| using the largest v_z and
// the smallest (or largest) v_x^2 + v_y^2.
double max_cos_to_box(const glm::dvec3& axis, const glm::dvec3& lo, const glm::dvec3& hi) {
    // Orthonormal frame (t, b, axis); Duff et al.'s branchless construction.
    const double sign = std::copysign(1.0, axis.z);
    const double a = -1.0 / (sign + axis.z);
    const double b = axis.x * axis.y * a;
    const glm::dvec3 t(1.0 + sign * axis.x * axis.x * a, sign * b, -sign * axis.x);
    const glm::dvec3 s(b, sign + axis.y * axis.y * a, -axis.y);

    const glm::dvec3 center = 0.5 * (lo + hi);
    const glm::dvec3 half_extent = 0.5 * (hi - lo);
    const glm::dvec3 local(glm::dot(center, t), glm::dot(center, s), glm::dot(center, axis));
    glm::dvec3 reach(glm::dot(half_extent, glm::abs(t)), glm::dot(half_extent, glm::abs(s)),
                           glm::dot(half_extent, glm::abs(axis)));
    // Rounding must not shrink the box: widen it by a few double ulps of the
    // largest terms the dot products summed (a grazing corner cancels them).
    const glm::dvec3 magnitude(glm::dot(glm::abs(center), glm::abs(t)),
                               glm::dot(glm::abs(center), glm::abs(s)),
                               glm::dot(glm::abs(center), glm::abs(axis)));
    reach += (magnitude + reach) * 1e-15;
    const glm::dvec3 llo = local - reach;
    const glm::dvec3 lhi = local + reach;
    const double z_max = lhi.z;
    auto min_sq = [](double l, double h) {
        return (l <= 0.0 && h >= 0.0) ? 0.0 : std::min(l * l, h * h);
    };
    auto max_sq = [](double l, double h) { return std::max(l * l, h * h); };
    if (z_max >= 0.0) {
        const double denom2 = min_sq(llo.x, lhi.x) + min_sq(llo.y, lhi.y) + z_max * z_max;
        if (!(denom2 > 0.0)) return 1.0;  // the box touches the origin
        return std::min(1.0, z_max / std::sqrt(denom2));
    }
    const double denom2 = max_sq(llo.x, lhi.x) + max_sq(llo.y, lhi.y) + z_max * z_max;
    return std::max(-1.0, z_max / std::sqrt(denom2));
}

// True when no light of a spot cluster can light p: every spot emits only
// within pi/2 of its own direction (outer <= pi/2), and every direction lies
// within beta of the cone axis, so a p seen from the box at more than
// pi/2 + beta from the axis is dark. Per-light outer angles are not stored on
// the node, so pi/2 is the only safe one. The cone is the compact node's (the
// shaders' one, widened by its packing).
bool spot_cluster_excluded(const CompactBounds& bounds, const SurfacePoint& p) {
    const double cone_cos = bounds.cone_cos;
    if (!(cone_cos >= -1.0 && cone_cos <= 1.0)) return false;
    const double beta = std::acos(cone_cos);
    const double limit = std::numbers::pi / 2.0 + beta;
    if (limit >= std::numbers::pi) return false;
    // Vectors from the lights to p: p - y for y in the box.
    const glm::dvec3 lo = p.position - bounds.bbox_max;
    const glm::dvec3 hi = p.position - bounds.bbox_min;
    const double cos_bound = max_cos_to_box(bounds.cone_axis, lo, hi);
    const double min_angle = std::acos(std::clamp(cos_bound, -1.0, 1.0));
    return min_angle > limit + 1e-9;
}

// Upper bound of G (shading_model.h, cosine with the normal included) over
// every light of the node, whose box and cone come from its compact node.
double geometric_bound(const LightTreeNode& node, const CompactBounds& bounds,
                       const SurfacePoint& p) {
    const glm::dvec3& bmin = bounds.bbox_min;
    const glm::dvec3& bmax = bounds.bbox_max;
    if (node.type == LightType::kDirectional) {
        // The box holds the directions d_i; the light arrives along -d_i.
        return std::max(0.0, max_cos_to_box(p.normal, -bmax, -bmin));
    }
    // Influence radius: every light's sphere of influence lies inside the
    // sphere of `radius` around `position`, so each range_i <= radius. A leaf
    // uses its own range; an unbounded representative makes the node unbounded.
    double radius =
        node.is_leaf() ? (node.range > 0.0f ? double(node.range) : -1.0) : double(node.radius);
    if (node.range <= 0.0f) radius = -1.0;
    if (radius >= 0.0) {
        const double center_distance = glm::length(p.position - glm::dvec3(node.position));
        if (center_distance >= radius) return 0.0;
    }
    const glm::dvec3 closest = glm::clamp(p.position, bmin, bmax);
    const double dmin2 = glm::dot(p.position - closest, p.position - closest);
    const double window = radius >= 0.0 ? shading::range_window(std::sqrt(dmin2), radius) : 1.0;
    if (!(window > 0.0)) return 0.0;
    const double cos_bound = max_cos_to_box(p.normal, bmin - p.position, bmax - p.position);
    if (!(cos_bound > 0.0)) return 0.0;
    if (node.type == LightType::kSpot && spot_cluster_excluded(bounds, p)) return 0.0;
    return cos_bound * window * shading::inverse_square(dmin2);
}

// One node of the bound criterion's cut.
struct CutEntry {
    double key = 0.0;  // max channel of the error bound; +inf forces refinement
    int32_t node = 0;
    glm::dvec3 unit{0.0};      // representative's response per unit intensity
    glm::dvec3 estimate{0.0};  // unit * cluster intensity (paper Eq. 2)
};

// Max-heap on the bound; equal bounds pop the smaller node index first, so the
// cut does not depend on the heap's internals.
bool heap_less(const CutEntry& a, const CutEntry& b) {
    if (a.key != b.key) return a.key < b.key;
    return a.node > b.node;
}

CutEntry make_entry(const LightTree& tree, int32_t index, const SurfacePoint& p,
                    const glm::dvec3* reuse_unit) {
    const LightTreeNode& node = tree.nodes[size_t(index)];
    CutEntry e;
    e.node = index;
    e.unit = reuse_unit ? *reuse_unit : unit_response(emitter_of(node), p);
    e.estimate = e.unit * glm::dvec3(node.intensity);
    int32_t children[2];
    if (valid_children(tree, index, children) == 0) {
        e.key = 0.0;  // a leaf is exact
    } else if (node.mixed_types) {
        e.key = std::numeric_limits<double>::infinity();
    } else {
        e.key = max_channel(node_contribution_bound(node, p));
    }
    return e;
}

void shade_classic(std::span<const SceneLight> classic_lights, const SurfacePoint& p,
                   CutResult& result) {
    for (const SceneLight& light : classic_lights) result.radiance += shade_light(light, p);
}

CutResult radius_cut(const LightTree& tree, const SurfacePoint& p) {
    CutResult result;
    std::vector<int32_t> stack{0};
    while (!stack.empty()) {
        const int32_t index = stack.back();
        stack.pop_back();
        const LightTreeNode& node = tree.nodes[size_t(index)];
        int32_t children[2];
        const int child_count = valid_children(tree, index, children);
        bool refine = false;
        if (child_count > 0) {
            if (node.mixed_types || node.radius < 0.0f) {
                refine = true;
            } else {
                const double d = glm::length(p.position - glm::dvec3(node.position));
                refine = d < double(node.radius);
            }
        }
        if (refine) {
            for (int c = child_count - 1; c >= 0; --c) stack.push_back(children[c]);
        } else {
            result.radiance += shade_node(node, p);
            result.cut_size += 1;
            result.cut_hash += cut_hash_term(uint32_t(index));
        }
    }
    return result;
}

CutResult bound_cut(const LightTree& tree, const SurfacePoint& p, const CutSettings& settings) {
    const double error_ratio = settings.error_ratio >= 0.0 ? settings.error_ratio : 0.0;
    const size_t max_cut = std::max<uint32_t>(settings.max_cut, 1);
    CutResult result;
    std::vector<CutEntry> heap{make_entry(tree, 0, p, nullptr)};
    glm::dvec3 total = heap.front().estimate;
    while (!heap.empty()) {
        const CutEntry& top = heap.front();
        if (!std::isinf(top.key)) {
            if (!(top.key > 0.0)) break;
            if (top.key <= error_ratio * std::max(max_channel(total), 0.0)) break;
            if (heap.size() >= max_cut) {
                result.max_cut_hit = true;
                break;
            }
        }
        std::pop_heap(heap.begin(), heap.end(), heap_less);
        const CutEntry parent = heap.back();
        heap.pop_back();
        total -= parent.estimate;
        const int32_t representative = tree.nodes[size_t(parent.node)].representative;
        int32_t children[2];
        const int child_count = valid_children(tree, parent.node, children);
        for (int c = 0; c < child_count; ++c) {
            // The child that shares the representative reuses its evaluation.
            const bool shares = tree.nodes[size_t(children[c])].representative == representative;
            CutEntry child = make_entry(tree, children[c], p, shares ? &parent.unit : nullptr);
            total += child.estimate;
            heap.push_back(child);
            std::push_heap(heap.begin(), heap.end(), heap_less);
        }
    }
    // The running total drifts with 1e12 intensity ratios; sum afresh.
    for (const CutEntry& entry : heap) {
        result.radiance += entry.estimate;
        result.cut_hash += cut_hash_term(uint32_t(entry.node));
    }
    result.cut_size = static_cast<uint32_t>(heap.size());
    return result;
}

}  // namespace

int valid_children(const LightTree& tree, int32_t index, int32_t out[2]) {
    const LightTreeNode& node = tree.nodes[size_t(index)];
    const int32_t size = static_cast<int32_t>(tree.nodes.size());
    int count = 0;
    for (int32_t child : {node.left, node.right}) {
        if (child > index && child < size) out[count++] = child;
    }
    return count;
}

uint32_t cut_hash_term(uint32_t node_index) {
    // murmur3's fmix32 finaliser of i + 1 (so node 0 does not hash to 0).
    uint32_t h = node_index + 1u;
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

glm::dvec3 shade_light(const SceneLight& light, const SurfacePoint& p) {
    const glm::dvec3 intensity = glm::dvec3(light.color) * double(light.intensity);
    return unit_response(emitter_of(light), p) * intensity;
}

glm::dvec3 shade_node(const LightTreeNode& node, const SurfacePoint& p) {
    return unit_response(emitter_of(node), p) * glm::dvec3(node.intensity);
}

glm::dvec3 shade_reference(std::span<const SceneLight> lights, const SurfacePoint& p) {
    glm::dvec3 sum(0.0);
    for (const SceneLight& light : lights) sum += shade_light(light, p);
    return sum;
}

glm::dvec3 shade_tree_leaves(const LightTree& tree, const SurfacePoint& p) {
    glm::dvec3 sum(0.0);
    for (const LightTreeNode& node : tree.nodes) {
        if (node.is_leaf()) sum += shade_node(node, p);
    }
    return sum;
}

glm::dvec3 node_contribution_bound(const LightTreeNode& node, const SurfacePoint& p) {
    if (node.mixed_types && !node.is_leaf()) {
        return glm::dvec3(std::numeric_limits<double>::infinity());
    }
    // A relative 1e-9 of slack absorbs the rounding of the bound's own arithmetic.
    const double G = geometric_bound(node, compact_bounds(node), p) * (1.0 + 1e-9);
    if (!(G > 0.0)) return glm::dvec3(0.0);
    return material_bound(node, p) * G * glm::dvec3(node.intensity);
}

glm::dvec3 material_response(const SurfacePoint& p, const glm::dvec3& l) {
    if (!has_lobe(p)) return diffuse_term(p);
    return diffuse_term(p) + p.specular * shading::glossy_lobe(glm::dot(p.mirror, l), p.exponent);
}

glm::dvec3 material_bound(const LightTreeNode& node, const SurfacePoint& p) {
    if (!has_lobe(p)) return diffuse_term(p);
    const CompactBounds bounds = compact_bounds(node);
    const glm::dvec3& bmin = bounds.bbox_min;
    const glm::dvec3& bmax = bounds.bbox_max;
    // Directions towards the lights: -d_i for directional boxes, y - x otherwise.
    const double cos_max = node.type == LightType::kDirectional
                               ? max_cos_to_box(p.mirror, -bmax, -bmin)
                               : max_cos_to_box(p.mirror, bmin - p.position, bmax - p.position);
    // The lobe's own rounding (pow of a number near 1) gets the same slack as G.
    return diffuse_term(p) +
           p.specular * (shading::glossy_lobe(cos_max, p.exponent) * (1.0 + 1e-9));
}

CutResult shade_lightcuts(const LightTree& tree, std::span<const SceneLight> classic_lights,
                          const SurfacePoint& p, const CutSettings& settings) {
    CutResult result;
    if (!tree.empty()) {
        if (settings.criterion == CutCriterion::kRadius) {
            result = radius_cut(tree, p);
        } else {
            result = settings.search == BoundSearch::kWalk ? bound_walk_cut(tree, p, settings)
                                                           : bound_cut(tree, p, settings);
        }
    }
    shade_classic(classic_lights, p, result);
    return result;
}

}  // namespace lc
