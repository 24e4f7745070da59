#include "lightcuts/tree/tree_export.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace lc {
namespace {

constexpr float kFloatMax = std::numeric_limits<float>::max();
// Breadth-first order visits the arena (10^6 nodes of 160 bytes) almost at
// random: ask for nodes this many steps ahead so their cache misses overlap.
constexpr size_t kPrefetchAhead = 16;

float nearest_float(double value) {
    return float(std::clamp(value, -double(kFloatMax), double(kFloatMax)));
}

glm::vec3 nearest_vec3(const glm::dvec3& v) {
    return glm::vec3(nearest_float(v.x), nearest_float(v.y), nearest_float(v.z));
}

glm::vec3 round_down(const glm::dvec3& v) {
    return glm::vec3(round_down_to_float(v.x), round_down_to_float(v.y), round_down_to_float(v.z));
}

glm::vec3 round_up(const glm::dvec3& v) {
    return glm::vec3(round_up_to_float(v.x), round_up_to_float(v.y), round_up_to_float(v.z));
}

float export_radius(double radius) {
    if (radius < 0.0 || radius > double(kFloatMax)) return kUnboundedRadius;
    return round_up_to_float(radius);
}

// The float axis may be off by ~1e-7 rad, so widen the half-angle by more
// than that before rounding the cosine down.
float export_cone_cos(double cone_cos) {
    constexpr double kAxisRoundingMargin = 0x1.0p-20;  // ~9.5e-7 rad
    if (cone_cos <= -1.0) return -1.0f;
    const double theta = std::acos(std::min(cone_cos, 1.0)) + kAxisRoundingMargin;
    if (theta >= std::numbers::pi) return -1.0f;
    return std::clamp(round_down_to_float(std::cos(theta)), -1.0f, 1.0f);
}

// Nodes [begin, end) of the breadth-first `order`, converted into `out_nodes`.
// A node's children sit side by side in that order, from first_child[i].
void convert_nodes(const BuildArena& arena, const std::vector<uint32_t>& order,
                   const std::vector<int32_t>& first_child, const std::vector<int32_t>& exported_index,
                   size_t begin, size_t end, std::vector<LightTreeNode>& out_nodes) {
    for (size_t i = begin; i < end; ++i) {
        // The node two strides ahead (a leaf's light), then (once it has
        // arrived) what it points at.
        if (i + 2 * kPrefetchAhead < end) {
            const uint32_t ahead = order[i + 2 * kPrefetchAhead];
            if (arena.is_leaf_index(ahead)) {
                prefetch_light(arena.lights[ahead]);
            } else {
                prefetch_build_node(arena.nodes[ahead]);
            }
        }
        if (i + kPrefetchAhead < end) {
            const uint32_t ahead = order[i + kPrefetchAhead];
            const uint32_t representative = arena.representative_of(ahead);
            prefetch_light(arena.lights[representative]);
            __builtin_prefetch(&exported_index[representative]);
        }
        const BuildNode node = arena.node(order[i]);
        out_nodes[i] = export_node(node, arena.representative_light(node), first_child[i],
                                   exported_index[node.representative]);
    }
}

}  // namespace

float round_down_to_float(double value) {
    if (value >= double(kFloatMax)) return kFloatMax;
    if (value <= -double(kFloatMax)) return -kFloatMax;
    const float f = float(value);
    return double(f) > value ? std::nextafter(f, -kFloatMax) : f;
}

float round_up_to_float(double value) {
    if (value >= double(kFloatMax)) return kFloatMax;
    if (value <= -double(kFloatMax)) return -kFloatMax;
    const float f = float(value);
    return double(f) < value ? std::nextafter(f, kFloatMax) : f;
}

LightTreeNode export_node(const BuildNode& node, const SceneLight& light, int32_t first_child,
                          int32_t representative_index) {
    LightTreeNode out;
    out.guid = node.guid;
    out.type = node.type;
    const bool has_left = node.left != kNoChild;
    out.left = has_left ? first_child : kNoChild;
    out.right = node.right == kNoChild ? kNoChild : first_child + (has_left ? 1 : 0);
    out.representative = representative_index;

    out.position = light.position;
    out.direction = light.direction;
    out.range = light.range;
    out.spot_cos_inner = std::cos(light.inner_cone_angle);
    out.spot_cos_outer = std::cos(light.outer_cone_angle);

    out.intensity = nearest_vec3(node.intensity);
    out.brightness = nearest_float(node.brightness);
    out.radius = export_radius(node.radius);
    out.falloff_exponent = 2.0f;
    out.bbox_min = round_down(node.bbox_min);
    out.bbox_max = round_up(node.bbox_max);
    out.cone_axis = glm::vec3(node.cone_axis);
    out.cone_cos = export_cone_cos(node.cone_cos);
    out.flags = node.flags;
    out.source_radius = light.source_radius;
    out.bounce = node.left == kNoChild && node.right == kNoChild ? light.bounce : uint16_t{0};
    return out;
}

ExportedTree export_light_tree(const BuildArena& arena, int32_t root, const ParallelRanges& parallel) {
    ExportedTree result;
    if (root < 0) return result;

    // Breadth-first order, where each exported node's children start, and
    // each leaf's exported index (the representatives are leaves).
    std::vector<uint32_t> order;
    order.reserve(arena.nodes.size());
    std::vector<int32_t> first_child;
    first_child.reserve(arena.nodes.size());
    std::vector<int32_t> exported_index(arena.lights.size(), kNoChild);
    order.push_back(uint32_t(root));
    // Leaves sit first in the arena, one per light (build_tree.h): a leaf is
    // known by its index, so the walk reads only the clusters.
    const auto is_leaf_index = [&](uint32_t index) { return arena.is_leaf_index(index); };
    // The depth grows by one each time the walk passes the end of a level.
    size_t level_end = 1;
    for (size_t head = 0; head < order.size(); ++head) {
        if (head == level_end) {
            ++result.depth;
            level_end = order.size();
        }
        if (head + kPrefetchAhead < order.size() && !is_leaf_index(order[head + kPrefetchAhead])) {
            __builtin_prefetch(&arena.nodes[order[head + kPrefetchAhead]]);
        }
        first_child.push_back(int32_t(order.size()));
        if (is_leaf_index(order[head])) {
            exported_index[order[head]] = int32_t(head);
            ++result.tree.leaf_count;
            continue;
        }
        const BuildNode& node = arena.nodes[order[head]];
        for (const int32_t child : {node.left, node.right}) {
            if (child != kNoChild) order.push_back(uint32_t(child));
        }
    }

    LightTree& tree = result.tree;
    tree.nodes.resize(order.size());
    const auto convert = [&](size_t begin, size_t end) {
        convert_nodes(arena, order, first_child, exported_index, begin, end, tree.nodes);
    };
    if (parallel) {
        parallel(order.size(), convert);
    } else {
        convert(0, order.size());
    }
    return result;
}

}  // namespace lc
