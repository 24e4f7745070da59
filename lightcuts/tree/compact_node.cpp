#include "lightcuts/tree/compact_node.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "lightcuts/device/octahedral.glsl.h"

namespace lc {
namespace {

// GLSL's packSnorm2x16 for one coordinate in [-1, 1].
uint32_t pack_snorm16(double v) {
    const double q = std::round(std::clamp(v, -1.0, 1.0) * 32767.0);
    return uint32_t(uint16_t(int16_t(q)));
}

// What the shaders add on top of the packing's own error: their float decode
// and normalisation differ from this double one by a few float ulps.
constexpr double kDecodeSlack = 1e-6;

}  // namespace

uint32_t encode_octahedral(const glm::dvec3& unit) {
    const double l1 = std::abs(unit.x) + std::abs(unit.y) + std::abs(unit.z);
    double x = unit.x / l1;
    double y = unit.y / l1;
    if (unit.z < 0.0) {
        const double folded_x = (1.0 - std::abs(y)) * octahedral::sign_not_zero(x);
        y = (1.0 - std::abs(x)) * octahedral::sign_not_zero(y);
        x = folded_x;
    }
    return pack_snorm16(x) | (pack_snorm16(y) << 16);
}

glm::dvec3 decode_octahedral(uint32_t bits) { return octahedral::decode_octahedral(bits); }

GpuTreeNode make_compact_node(const LightTreeNode& node, uint32_t representative, float representative_range,
                              int32_t first_child, int32_t escape) {
    GpuTreeNode out;
    out.intensity = node.intensity;
    out.representative = representative;
    out.bbox_min = node.bbox_min;
    out.bbox_max = node.bbox_max;
    out.first_child = first_child;
    out.escape = escape;
    out.radius = node.radius;
    out.flags = node.flags.bits | (representative_range > 0.0f ? kNodeBoundedRepresentative : 0u) |
                (uint32_t(node.type) << kNodeTypeShift);
    // A cone that excludes nothing, or that nothing can be learnt from,
    // becomes "every direction" (the bound then excludes nothing either).
    const glm::dvec3 axis(node.cone_axis);
    const double axis_len = glm::length(axis);
    const double cone_cos = node.cone_cos;
    out.cone_axis = encode_octahedral(glm::dvec3(0.0, 0.0, 1.0));
    out.cone_cos = -1.0f;
    if (!(cone_cos >= -1.0 && cone_cos <= 1.0) || !(axis_len > 0.0) || !std::isfinite(axis_len))
        return out;
    const glm::dvec3 unit = axis / axis_len;
    out.cone_axis = encode_octahedral(unit);
    const glm::dvec3 decoded = decode_octahedral(out.cone_axis);
    const double moved = std::acos(std::clamp(glm::dot(unit, decoded), -1.0, 1.0));
    const double half_angle = std::acos(cone_cos) + moved + kDecodeSlack;
    if (half_angle >= std::acos(-1.0)) return out;
    // Rounded down: the float cosine never narrows the cone.
    float widened = float(std::cos(half_angle));
    if (double(widened) > std::cos(half_angle))
        widened = std::nextafter(widened, -std::numeric_limits<float>::infinity());
    out.cone_cos = std::max(widened, -1.0f);
    return out;
}

CompactBounds decode_box(const GpuTreeNode& node) {
    CompactBounds b;
    b.bbox_min = glm::dvec3(node.bbox_min);
    b.bbox_max = glm::dvec3(node.bbox_max);
    return b;
}

CompactBounds decode_bounds(const GpuTreeNode& node) {
    CompactBounds b = decode_box(node);
    b.cone_axis = decode_octahedral(node.cone_axis);
    b.cone_cos = node.cone_cos;
    return b;
}

}  // namespace lc
