#pragma once
// The light tree's nodes as the GPU and the CPU evaluator walk them
// (walk_tree.h): GpuTreeNode (lightcuts/device/gpu_structs.h), 64 bytes, made from a
// float tree node and decoded back in this one place (pbrt-v4's
// CompactLightBounds is the model). No light parameter is quantised: the node
// names its representative leaf, whose light the shader reads, and carries the
// cluster's RGB intensity. Only the spot cone's axis is packed (octahedral,
// 2 x 16 bits); the cone is widened by the angle the packing moved its axis,
// its cosine rounded down, so every direction the cone held stays inside it.
#include <glm/vec3.hpp>

#include <cstdint>

#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/tree/light_tree.h"

namespace lc {

// A unit vector in 32 bits and back (octahedral map, snorm16 per coordinate,
// as GLSL's packSnorm2x16 / unpackSnorm2x16).
uint32_t encode_octahedral(const glm::dvec3& unit);
glm::dvec3 decode_octahedral(uint32_t bits);

// The compact node of `node`; `representative` is its representative's index
// among the tree's leaves (leaf_lights) and `representative_range` its range,
// first_child and escape its walk links.
GpuTreeNode make_compact_node(const LightTreeNode& node, uint32_t representative, float representative_range,
                              int32_t first_child, int32_t escape);

// What the bound criterion reads from a compact node, in double.
struct CompactBounds {
    glm::dvec3 bbox_min{0.0};  // the leaves' positions (directions for directional lights)
    glm::dvec3 bbox_max{0.0};
    glm::dvec3 cone_axis{0.0, 0.0, -1.0};  // unit
    double cone_cos = -1.0;                // -1: every direction
};
// The CPU evaluator bounds a node from the walk tree's compact node (the
// one the shaders read) through this, exactly as the shaders do.
CompactBounds decode_bounds(const GpuTreeNode& node);
// The box alone, the cone left as every direction (for lights that have none to read).
CompactBounds decode_box(const GpuTreeNode& node);

}  // namespace lc
