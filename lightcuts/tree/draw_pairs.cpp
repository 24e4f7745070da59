#include "lightcuts/tree/draw_pairs.h"

#include <glm/geometric.hpp>

#include <algorithm>

#include "lightcuts/device/pixel_representative.glsl.h"

namespace lc {
namespace {

struct ChildDraw {
    vec3 centre{0.0f};
    float radius = -1.0f;
    float intensity = 0.0f;
    int destination = 0;
};

// Directions, not positions, fill a directional child's box; a mixed child's
// box mixes both: either weighs by intensity alone.
bool weighs_by_intensity_alone(const GpuTreeNode& node) {
    return (node.flags & kNodeMixedTypes) != 0u || (node.flags >> kNodeTypeShift) == kLightDirectional;
}

ChildDraw child_draw(std::span<const GpuTreeNode> nodes, int index) {
    const GpuTreeNode& node = nodes[size_t(index)];
    ChildDraw draw;
    draw.intensity = device::representative_scalar(node.intensity);
    draw.destination = node.first_child == kNoChild ? ~int(node.representative) : index;
    if (!weighs_by_intensity_alone(node)) {
        draw.centre = 0.5f * (node.bbox_min + node.bbox_max);
        // Widened by a few ulps so that the sphere holds the box's corners
        // in float too: a child is weighed zero only when wholly behind.
        draw.radius = 0.5f * glm::length(node.bbox_max - node.bbox_min) * (1.0f + 1.0f / 65536.0f);
    }
    return draw;
}

}  // namespace

std::vector<GpuDrawPair> make_draw_pairs(std::span<const GpuTreeNode> nodes) {
    std::vector<GpuDrawPair> pairs(std::max<size_t>(nodes.size(), 1));
    for (size_t i = 0; i < nodes.size(); ++i) {
        const GpuTreeNode& node = nodes[i];
        if (node.first_child == kNoChild) continue;
        const int c0 = node.first_child;
        const int c1 = nodes[size_t(c0)].escape;
        // The first child's escape is its sibling, unless it is the parent's own.
        const bool two = c1 != kEndOfWalk && c1 != node.escape;
        const ChildDraw first = child_draw(nodes, c0);
        const ChildDraw second = two ? child_draw(nodes, c1) : first;
        GpuDrawPair& pair = pairs[i];
        pair.centre0 = first.centre;
        pair.radius0 = first.radius;
        pair.intensity0 = first.intensity;
        pair.child0 = first.destination;
        pair.centre1 = second.centre;
        pair.radius1 = second.radius;
        pair.intensity1 = two ? second.intensity : 0.0f;
        pair.child1 = second.destination;
    }
    return pairs;
}

}  // namespace lc
