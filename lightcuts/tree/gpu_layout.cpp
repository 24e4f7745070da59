#include "lightcuts/tree/gpu_layout.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "lightcuts/check.h"
#include "lightcuts/tree/compact_node.h"
#include "lightcuts/shading_model.h"

namespace lc {

static_assert(kLightPoint == uint(LightType::kPoint) && kLightSpot == uint(LightType::kSpot) &&
              kLightDirectional == uint(LightType::kDirectional) &&
              kLightOriented == uint(LightType::kOriented));

namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

Status check_node_values(const LightTreeNode& node, size_t index) {
    auto bad = [index](const char* field) {
        return make_error("tree node " + std::to_string(index) + ": " + field + " is not finite");
    };
    if (!finite(node.position)) return bad("position");
    if (!finite(node.direction)) return bad("direction");
    if (!finite(node.intensity)) return bad("intensity");
    if (!std::isfinite(node.radius)) return bad("radius");
    if (!std::isfinite(node.range)) return bad("range");
    if (!std::isfinite(node.spot_cos_inner) || !std::isfinite(node.spot_cos_outer))
        return bad("spot cone");
    if (static_cast<int>(node.type) >= kLightTypeCount)
        return make_error("tree node " + std::to_string(index) + ": unknown light type " +
                          std::to_string(static_cast<int>(node.type)));
    return Ok{};
}

}  // namespace

GpuLight make_gpu_light(const SceneLight& light) {
    GpuLight gpu;
    gpu.position = light.position;
    gpu.range = light.range;
    gpu.direction = light.direction;
    gpu.type = static_cast<uint32_t>(light.type);
    gpu.intensity = light.color * light.intensity;
    double cos_inner = std::cos(double(light.inner_cone_angle));
    double cos_outer = std::cos(double(light.outer_cone_angle));
    gpu.spot_cos_inner = float(cos_inner);
    gpu.spot_cos_outer = float(cos_outer);
    gpu.spot_scale = float(shading::spot_scale(cos_inner, cos_outer));
    gpu.flags = (light.indirect ? kGpuLightIndirect : 0u) | (light.patch ? kGpuLightPatch : 0u);
    gpu.source_radius = light.source_radius;
    return gpu;
}

GpuLight make_gpu_leaf_light(const LightTreeNode& node) {
    GpuLight gpu;
    gpu.position = node.position;
    gpu.range = node.range;
    gpu.direction = node.direction;
    gpu.type = static_cast<uint32_t>(node.type);
    gpu.intensity = node.intensity;
    gpu.spot_cos_inner = node.spot_cos_inner;
    gpu.spot_cos_outer = node.spot_cos_outer;
    gpu.spot_scale = float(shading::spot_scale(node.spot_cos_inner, node.spot_cos_outer));
    gpu.flags = (node.flags.indirect() ? kGpuLightIndirect : 0u) | (node.flags.patch() ? kGpuLightPatch : 0u);
    gpu.source_radius = node.source_radius;
    return gpu;
}

Result<std::vector<int32_t>> derive_escape_indices(const LightTree& tree) {
    const size_t n = tree.nodes.size();
    if (n > size_t(INT32_MAX)) return make_error("tree has too many nodes for 32-bit indices");
    std::vector<int32_t> escape(n, kEndOfWalk);
    std::vector<uint8_t> has_parent(n, 0);
    // Every child index is checked before any escape is propagated through it.
    for (size_t i = 0; i < n; ++i) {
        const LightTreeNode& node = tree.nodes[i];
        for (int32_t child : {node.left, node.right}) {
            if (child == kNoChild) continue;
            if (child < 0 || size_t(child) >= n)
                return make_error("tree node " + std::to_string(i) + ": child index " +
                                  std::to_string(child) + " is out of range (" + std::to_string(n) +
                                  " nodes)");
            if (size_t(child) <= i)
                return make_error("tree node " + std::to_string(i) + ": child index " +
                                  std::to_string(child) +
                                  " is not greater than its parent's (breadth-first order)");
            if (has_parent[child])
                return make_error("tree node " + std::to_string(child) + " has two parents");
            has_parent[child] = 1;
        }
    }
    // Parents precede children, so a node's escape is final when we reach it.
    for (size_t i = 0; i < n; ++i) {
        const LightTreeNode& node = tree.nodes[i];
        if (node.left != kNoChild)
            escape[node.left] = node.right != kNoChild ? node.right : escape[i];
        if (node.right != kNoChild) escape[node.right] = escape[i];
    }
    return escape;
}

Result<WalkTree> make_walk_tree(const LightTree& tree) {
    Result<std::vector<int32_t>> escape = derive_escape_indices(tree);
    if (!escape) return make_error(escape.error());
    WalkTree gpu;
    const size_t n = tree.nodes.size();
    // Each leaf's index among the leaves (leaf_lights), where representatives point.
    constexpr uint32_t kNotALeaf = UINT32_MAX;
    std::vector<uint32_t> leaf_index(n, kNotALeaf);
    uint32_t leaf_count = 0;
    for (size_t i = 0; i < n; ++i)
        if (tree.nodes[i].is_leaf()) leaf_index[i] = leaf_count++;
    gpu.nodes.resize(n);
    gpu.leaves.reserve(leaf_count);
    std::vector<uint32_t> depth(n, 0);
    for (size_t i = 0; i < n; ++i) {
        const LightTreeNode& node = tree.nodes[i];
        Status values = check_node_values(node, i);
        if (!values) return make_error(values.error());
        // A leaf represents itself.
        const int32_t representative = node.is_leaf() ? int32_t(i) : node.representative;
        if (representative < 0 || size_t(representative) >= n ||
            leaf_index[size_t(representative)] == kNotALeaf)
            return make_error("tree node " + std::to_string(i) + ": representative " +
                              std::to_string(representative) + " is not a leaf");
        const int32_t first_child = node.left != kNoChild ? node.left : node.right;
        gpu.nodes[i] = make_compact_node(node, leaf_index[size_t(representative)],
                                         tree.nodes[size_t(representative)].range, first_child, (*escape)[i]);
        for (int32_t child : {node.left, node.right})
            if (child != kNoChild) depth[child] = depth[i] + 1;
        gpu.depth = std::max(gpu.depth, depth[i]);
        if (node.is_leaf()) {
            if (node.flags.mixed_types())
                return make_error("tree node " + std::to_string(i) +
                                  " is a leaf marked as joining light types");
            gpu.leaves.push_back(make_gpu_leaf_light(node));
        }
    }
    // The links were checked above, so these hold unless this function is wrong.
    LC_CHECK(gpu.leaves.size() == leaf_count);
    LC_CHECK(n == 0 || gpu.depth < n);
    return gpu;
}

}  // namespace lc
