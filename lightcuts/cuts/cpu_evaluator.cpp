// The CPU evaluator in double precision: the ground truth the shaders are
// tested against. Its formulas are the shaders' own (lightcuts/device/*.glsl.h,
// compiled here in double); its cut searches share cut_traversal.h.
//
// Conventions the GPU mirrors:
// - A shading point exactly on a light (d = 0) gets nothing from it: the
//   direction to the light is undefined.
// - Radius criterion: a node is refined while |p - position| < radius
//   (strictly; radius < 0 means unbounded, always inside), or when it is a
//   kNodeMixedTypes junction.
// - Bound criterion: colours are compared through their largest channel:
//   a node is refined while max_c(bound_c) > error_ratio * max_c(total_c).
// - Indirect lights: the cut is chosen from unclamped estimates; then each
//   indirect leaf on it is clamped to half the error ratio of the cut's total
//   (device/indirect_clamp.glsl.h), before the classic lights are added; the
//   reference (every leaf) clamps them exactly (exact_indirect_clamp.h).
#include "lightcuts/cuts/cpu_evaluator.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "lightcuts/cuts/bound_walk.h"
#include "lightcuts/check.h"
#include "lightcuts/tree/compact_node.h"
#include "lightcuts/cuts/cut_traversal.h"
#include "lightcuts/device/cluster_bounds.glsl.h"
#include "lightcuts/device/cut_hash.glsl.h"
#include "lightcuts/device/pixel_representative.glsl.h"
#include "lightcuts/cuts/exact_indirect_clamp.h"
#include "lightcuts/material_model.h"
#include "lightcuts/shading_model.h"
#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/occlusion/shadow_ray.h"

namespace lc {

static_assert(uint32_t(Representatives::kTree) == device::kRepresentativesTree &&
              uint32_t(Representatives::kPixel) == device::kRepresentativesPixel &&
              uint32_t(Representatives::kImportance) == device::kRepresentativesImportance);

namespace {

shading::Emitter make_emitter(LightType type, const glm::vec3& position, const glm::vec3& direction,
                              double range, double cos_inner, double cos_outer, double source_radius) {
    shading::Emitter e;
    e.directional = type == LightType::kDirectional;
    e.spot = type == LightType::kSpot;
    e.oriented = type == LightType::kOriented;
    e.position = glm::dvec3(position);
    e.direction = glm::dvec3(direction);
    e.range = range;
    e.cos_outer = cos_outer;
    e.spot_scale = shading::spot_scale(cos_inner, cos_outer);
    e.source_radius = source_radius;
    return e;
}

shading::Emitter emitter_of(const SceneLight& light) {
    return make_emitter(light.type, light.position, light.direction, light.range,
                        std::cos(double(light.inner_cone_angle)), std::cos(double(light.outer_cone_angle)),
                        light.source_radius);
}

// A node's representative is read here only (a leaf light), its bounds in cluster_shape_of().
shading::Emitter emitter_of(const GpuLight& light) {
    return make_emitter(LightType(light.type), light.position, light.direction, light.range,
                        light.spot_cos_inner, light.spot_cos_outer, light.source_radius);
}

// The box and cone the shaders see, decoded from the compact node; the
// position and range are the representative's.
shading::ClusterShape cluster_shape_of(const WalkTree& tree, int32_t index) {
    const GpuTreeNode& node = tree.node(index);
    const GpuLight& representative = tree.light_of(index);
    const LightType type = node_type(node);
    shading::ClusterShape c;
    c.directional = type == LightType::kDirectional;
    c.spot = type == LightType::kSpot;
    c.oriented = type == LightType::kOriented;
    c.leaf = is_leaf(node);
    c.position = glm::dvec3(representative.position);
    c.range = representative.range;
    c.radius = node.radius;
    // Only spots and oriented lights read the cone: the others skip unpacking its axis.
    const CompactBounds bounds = c.spot || c.oriented ? decode_bounds(node) : decode_box(node);
    c.bbox_min = bounds.bbox_min;
    c.bbox_max = bounds.bbox_max;
    c.cone_axis = bounds.cone_axis;
    c.cone_cos = bounds.cone_cos;
    return c;
}

// Outgoing radiance per unit RGB intensity: f_r * G * V.
glm::dvec3 unit_response(LightType type, const shading::Emitter& e, const SurfacePoint& p) {
    glm::dvec3 l(0.0);
    double G = shading::light_geometry(e, p.position, p.normal, l);
    if (G > 0.0 && p.occluders != nullptr)
        G *= light_visibility(*p.occluders, p.shadow_bias, type, e.position, e.direction,
                              p.position, p.normal);
    return material_response(p, l) * G;
}

glm::dvec3 unit_response(const GpuLight& light, const SurfacePoint& p) {
    return unit_response(LightType(light.type), emitter_of(light), p);
}

// One node of the heap search's cut.
struct CutEntry {
    double key = 0.0;  // error_key(): +inf forces refinement
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

// Per unit intensity, what node `index` evaluated as a cluster returns (kTree
// and kPixel): its representative's response.
glm::dvec3 cluster_unit_response(const WalkTree& tree, int32_t index, const SurfacePoint& p,
                                 const CutSettings& settings) {
    if (settings.representatives == Representatives::kTree) return unit_response(tree.light_of(index), p);
    return unit_response(tree.leaves[pixel_draw(tree, index, p, settings).light], p);
}

// Whether child c of `parent` (children as children_of lists them) has
// its parent's evaluation per unit intensity (kImportance: never, its
// estimates scale by the draw's probability).
bool shares_representative(const WalkTree& tree, int32_t parent, const int32_t children[2], int child_count,
                           int c, const SurfacePoint& p, const CutSettings& settings) {
    if (settings.representatives == Representatives::kTree)
        return tree.node(children[c]).representative == tree.node(parent).representative;
    if (settings.representatives == Representatives::kImportance) return false;
    // The pixel's representative of the parent is the one of the child its draw takes there.
    const bool takes_first =
        child_count < 2 ||
        device::pixel_takes_first_child(pixel_representative_key(p, settings), uint32_t(parent),
                                        tree.node(children[0]).intensity, tree.node(children[1]).intensity);
    return (c == 0) == takes_first;
}

// A child's weight in the importance draw, in float as the shaders compute it.
float importance_weight(const GpuTreeNode& node, const SurfacePoint& p) {
    return device::importance_weight(
        node.intensity,
        device::importance_geometry(node.bbox_min, node.bbox_max, glm::vec3(p.position), glm::vec3(p.normal),
                                    node_type(node) == LightType::kDirectional));
}

CutEntry make_entry(const WalkTree& tree, int32_t index, const SurfacePoint& p, const CutSettings& settings,
                    const glm::dvec3* reuse_unit) {
    const GpuTreeNode& node = tree.node(index);
    CutEntry e;
    e.node = index;
    if (settings.representatives == Representatives::kImportance) {
        e.estimate = shade_cluster(tree, index, p, settings);
    } else {
        e.unit = reuse_unit ? *reuse_unit : cluster_unit_response(tree, index, p, settings);
        e.estimate = e.unit * glm::dvec3(node.intensity);
    }
    e.key = error_key(tree, index, p);
    return e;
}

// Refined while p lies strictly inside the node's influence radius (radius < 0:
// unbounded, always inside) around its representative, and always at a
// mixed-type junction.
CutResult radius_cut(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings) {
    const CutTally cut =
        walk_cut(tree, p, settings, [&](int32_t index, const GpuTreeNode& node, int child_count) {
            if (child_count == 0) return false;
            if (joins_types(node) || node.radius < 0.0f) return true;
            return glm::length(p.position - glm::dvec3(tree.light_of(index).position)) < double(node.radius);
        });
    CutResult result;
    cut.copy_to(result, indirect_clamp_ratio(settings.error_ratio));
    return result;
}

}  // namespace

CutResult bound_heap_cut(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings,
                         std::vector<CutNodeEstimate>* nodes) {
    const BoundRule rule(settings);
    CutResult result;
    if (left_out(tree.node(0), settings)) return result;
    std::vector<CutEntry> heap{make_entry(tree, 0, p, settings, nullptr)};
    glm::dvec3 total = heap.front().estimate;
    // The cut's indirect leaves (never refined, so only added): the rule reads
    // the clamped total.
    const double clamp_ratio = indirect_clamp_ratio(settings.error_ratio);
    device::IndirectSums leaves = device::no_indirect_sums();
    const auto add_if_indirect_leaf = [&](const CutEntry& entry) {
        const GpuTreeNode& node = tree.node(entry.node);
        if (device::clamped_leaf(is_indirect(node), is_patch(node), is_leaf(node)))
            device::add_indirect_leaf(leaves, entry.estimate);
    };
    const auto rule_total = [&] {
        return leaves.leaves > 0 ? device::clamped_running_total(total, leaves, clamp_ratio) : total;
    };
    add_if_indirect_leaf(heap.front());
    while (!heap.empty()) {
        const CutEntry& top = heap.front();
        if (!std::isinf(top.key)) {
            if (!(top.key > 0.0)) break;
            if (top.key <= rule.limit(rule_total())) break;
            if (heap.size() >= rule.max_cut) {
                result.max_cut_hit = true;
                break;
            }
        }
        std::pop_heap(heap.begin(), heap.end(), heap_less);
        const CutEntry parent = heap.back();
        heap.pop_back();
        total -= parent.estimate;
        int32_t children[2];
        const int child_count = children_of(tree, parent.node, children);
        for (int c = 0; c < child_count; ++c) {
            if (left_out(tree.node(children[c]), settings)) continue;
            // The child that shares the representative reuses its evaluation.
            const bool shares =
                shares_representative(tree, parent.node, children, child_count, c, p, settings);
            CutEntry child = make_entry(tree, children[c], p, settings, shares ? &parent.unit : nullptr);
            total += child.estimate;
            add_if_indirect_leaf(child);
            heap.push_back(child);
            std::push_heap(heap.begin(), heap.end(), heap_less);
        }
    }
    // The running total drifts with 1e12 intensity ratios; sum afresh.
    CutTally cut;
    for (const CutEntry& entry : heap) cut.add(entry.node, tree.node(entry.node), entry.estimate);
    cut.copy_to(result, clamp_ratio);
    if (nodes != nullptr) {
        for (const CutEntry& entry : heap) nodes->push_back({entry.node, entry.estimate});
    }
    return result;
}

uint32_t cut_hash_term(uint32_t node_index) { return device::cut_hash_term(node_index); }

uint32_t pixel_representative_key(const SurfacePoint& p, const CutSettings& settings) {
    return device::pixel_representative_key(p.pixel.x, p.pixel.y, settings.representative_seed);
}

namespace {

// A leaf node reached by a descent, with its probability.
struct Descent {
    int32_t leaf = 0;
    double probability = 1.0;
};

// The descent from node `index` to a leaf, each junction's child drawn in
// proportion to weight(child); the probability of the leaf reached.
template <typename Weight>
Descent descend(const WalkTree& tree, int32_t index, uint32_t key, Weight&& weight) {
    Descent draw{index, 1.0};
    // Children come after their parents, so the descent ends.
    for (;;) {
        int32_t children[2];
        const int child_count = children_of(tree, draw.leaf, children);
        if (child_count == 0) return draw;
        bool first = true;
        if (child_count == 2) {
            const float w0 = weight(tree.node(children[0]));
            const float w1 = weight(tree.node(children[1]));
            first = device::pixel_takes_first(key, uint32_t(draw.leaf), w0, w1);
            if (w0 + w1 > 0.0f) draw.probability *= double(first ? w0 : w1) / (double(w0) + double(w1));
        }
        draw.leaf = children[first ? 0 : 1];
    }
}

}  // namespace

int32_t pixel_representative(const WalkTree& tree, int32_t index, uint32_t key) {
    return descend(tree, index, key,
                   [](const GpuTreeNode& node) { return device::representative_scalar(node.intensity); })
        .leaf;
}

PixelDraw pixel_draw(const WalkTree& tree, int32_t index, const SurfacePoint& p,
                     const CutSettings& settings) {
    switch (settings.representatives) {
        case Representatives::kTree:
            break;
        case Representatives::kPixel:
            return {tree.node(pixel_representative(tree, index, pixel_representative_key(p, settings)))
                        .representative,
                    1.0};
        case Representatives::kImportance: {
            const Descent draw = descend(tree, index, pixel_representative_key(p, settings),
                                         [&](const GpuTreeNode& node) { return importance_weight(node, p); });
            return {tree.node(draw.leaf).representative, draw.probability};
        }
    }
    return {tree.node(index).representative, 1.0};  // a leaf represents itself
}

glm::dvec3 shade_cluster(const WalkTree& tree, int32_t index, const SurfacePoint& p,
                         const CutSettings& settings) {
    const GpuTreeNode& node = tree.node(index);
    if (settings.representatives == Representatives::kTree || is_leaf(node))
        return shade_node(tree, index, p);
    if (settings.representatives == Representatives::kPixel)
        return cluster_unit_response(tree, index, p, settings) * glm::dvec3(node.intensity);
    const PixelDraw draw = pixel_draw(tree, index, p, settings);
    if (!(draw.probability > 0.0)) return glm::dvec3(0.0);
    return shade_light(tree.leaves[draw.light], p) / draw.probability;
}

glm::dvec3 shade_light(const SceneLight& light, const SurfacePoint& p) {
    const glm::dvec3 intensity = glm::dvec3(light.color) * double(light.intensity);
    return unit_response(light.type, emitter_of(light), p) * intensity;
}

glm::dvec3 shade_light(const GpuLight& light, const SurfacePoint& p) {
    return unit_response(light, p) * glm::dvec3(light.intensity);
}

glm::dvec3 shade_node(const WalkTree& tree, int32_t index, const SurfacePoint& p) {
    return unit_response(tree.light_of(index), p) * glm::dvec3(tree.node(index).intensity);
}

glm::dvec3 shade_reference(std::span<const SceneLight> lights, const SurfacePoint& p) {
    glm::dvec3 sum(0.0);
    for (const SceneLight& light : lights) sum += shade_light(light, p);
    LC_DCHECK(std::isfinite(sum.x) && std::isfinite(sum.y) && std::isfinite(sum.z));
    return sum;
}

glm::dvec3 shade_tree_leaves(const WalkTree& tree, const SurfacePoint& p) {
    glm::dvec3 sum(0.0);
    for (const GpuLight& light : tree.leaves) sum += shade_light(light, p);
    LC_DCHECK(std::isfinite(sum.x) && std::isfinite(sum.y) && std::isfinite(sum.z));
    return sum;
}

glm::dvec3 node_contribution_bound(const WalkTree& tree, int32_t index, const SurfacePoint& p) {
    const GpuTreeNode& node = tree.node(index);
    if (joins_types(node) && !is_leaf(node)) return glm::dvec3(std::numeric_limits<double>::infinity());
    return shading::response_bound(cluster_shape_of(tree, index), p.albedo, p.specular, p.exponent, p.mirror,
                                   p.position, p.normal) *
           glm::dvec3(node.intensity);
}

glm::dvec3 material_response(const SurfacePoint& p, const glm::dvec3& l) {
    return shading::brdf(p.albedo, p.specular, p.exponent, p.mirror, l);
}

glm::dvec3 material_bound(const WalkTree& tree, int32_t index, const SurfacePoint& p) {
    return shading::material_bound(cluster_shape_of(tree, index), p.albedo, p.specular, p.exponent, p.mirror,
                                   p.position);
}

CutResult shade_tree_reference(const WalkTree& tree, std::span<const SceneLight> classic_lights,
                               const SurfacePoint& p, const CutSettings& settings) {
    CutResult result;
    glm::dvec3 others(0.0);
    std::vector<glm::dvec3> clamped_leaves;
    for (const GpuLight& light : tree.leaves) {
        if (left_out(light, settings)) continue;
        const glm::dvec3 contribution = shade_light(light, p);
        result.cut_size += 1;
        if (is_indirect(light)) result.indirect += contribution;
        if (device::clamped_leaf(is_indirect(light), is_patch(light), true)) {
            clamped_leaves.push_back(contribution);
        } else {
            others += contribution;
        }
    }
    const ExactClamp clamp =
        exact_indirect_clamp(others, clamped_leaves, indirect_clamp_ratio(settings.error_ratio));
    result.radiance = clamp.radiance;
    result.clamped = clamp.removed;
    for (const SceneLight& light : classic_lights) result.radiance += shade_light(light, p);
    return result;
}

CutResult shade_lightcuts(const WalkTree& tree, std::span<const SceneLight> classic_lights,
                          const SurfacePoint& p, const CutSettings& settings) {
    CutResult result;
    if (!tree.empty()) {
        if (settings.criterion == CutCriterion::kRadius) {
            result = radius_cut(tree, p, settings);
        } else {
            result = settings.search == BoundSearch::kWalk ? bound_walk_cut(tree, p, settings)
                                                           : bound_heap_cut(tree, p, settings);
        }
    }
    for (const SceneLight& light : classic_lights) result.radiance += shade_light(light, p);
    return result;
}

}  // namespace lc
