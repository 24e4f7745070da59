#include "lightcuts/tree_export.h"

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
void convert_nodes(const BuildArena& arena, const std::vector<uint32_t>& order,
                   const std::vector<int32_t>& exported_index, size_t begin, size_t end,
                   std::vector<LightTreeNode>& out_nodes) {
    for (size_t i = begin; i < end; ++i) {
        // The node two strides ahead, then (once it has arrived) what it points at.
        if (i + 2 * kPrefetchAhead < end) {
            __builtin_prefetch(&arena.nodes[order[i + 2 * kPrefetchAhead]]);
        }
        if (i + kPrefetchAhead < end) {
            const uint32_t representative = arena.nodes[order[i + kPrefetchAhead]].representative;
            __builtin_prefetch(&arena.lights[representative]);
            __builtin_prefetch(&exported_index[representative]);
        }
        const BuildNode& node = arena.nodes[order[i]];
        const SceneLight& light = arena.representative_light(node);
        LightTreeNode& out = out_nodes[i];
        out.guid = node.guid;
        out.type = node.type;
        out.left = node.left == kNoBuildChild ? kNoChild : exported_index[size_t(node.left)];
        out.right = node.right == kNoBuildChild ? kNoChild : exported_index[size_t(node.right)];
        out.representative = exported_index[node.representative];

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
        out.mixed_types = node.mixed_types;
        out.indirect = node.indirect;
        out.patch = node.patch;
        out.source_radius = light.source_radius;
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

ExportedTree export_light_tree(const BuildArena& arena, int32_t root, const ParallelRanges& parallel) {
    ExportedTree result;
    if (root < 0) return result;

    // Breadth-first order and each arena node's exported index.
    std::vector<uint32_t> order;
    order.reserve(arena.nodes.size());
    std::vector<int32_t> exported_index(arena.nodes.size(), kNoChild);
    std::vector<uint32_t> node_depth;
    node_depth.reserve(arena.nodes.size());
    order.push_back(uint32_t(root));
    node_depth.push_back(0);
    exported_index[size_t(root)] = 0;
    // Leaves sit first in the arena, one per light (build_tree.h): a leaf is
    // known by its index, so the walk reads only the clusters.
    const auto is_leaf_index = [&](uint32_t index) { return index < arena.lights.size(); };
    for (size_t head = 0; head < order.size(); ++head) {
        if (head + kPrefetchAhead < order.size() && !is_leaf_index(order[head + kPrefetchAhead])) {
            __builtin_prefetch(&arena.nodes[order[head + kPrefetchAhead]]);
        }
        result.depth = std::max(result.depth, node_depth[head]);
        if (is_leaf_index(order[head])) {
            ++result.tree.leaf_count;
            continue;
        }
        const BuildNode& node = arena.nodes[order[head]];
        for (const int32_t child : {node.left, node.right}) {
            if (child == kNoBuildChild) continue;
            exported_index[size_t(child)] = int32_t(order.size());
            order.push_back(uint32_t(child));
            node_depth.push_back(node_depth[head] + 1);
        }
    }

    LightTree& tree = result.tree;
    tree.nodes.resize(order.size());
    const auto convert = [&](size_t begin, size_t end) {
        convert_nodes(arena, order, exported_index, begin, end, tree.nodes);
    };
    if (parallel) {
        parallel(order.size(), convert);
    } else {
        convert(0, order.size());
    }
    return result;
}

}  // namespace lc
