#pragma once
// The light tree as it travels on the result channel and as the client
// imports it. Float precision, conservatively rounded from the server's
// double-precision build (see lightcuts/tree/tree_export.h). Every walk (the
// shaders, the CPU evaluator) reads its walk form instead, made once by
// make_walk_tree (walk_tree.h, gpu_layout.h).
#include <glm/vec3.hpp>

#include <cstdint>
#include <type_traits>
#include <vector>

#include "lightcuts/guid.h"
#include "lightcuts/scene_light.h"
#include "lightcuts/tree/node_flags.h"

namespace lc {

struct LightTreeNode {
    Guid guid;  // a leaf carries its scene light's GUID; a cluster a derived one
    LightType type = LightType::kPoint;
    // A VPL leaf: the bounce that left it (SceneLight::bounce); 0 otherwise.
    uint16_t bounce = 0;
    int32_t left = kNoChild;   // explicit child indices (never heap layout)
    int32_t right = kNoChild;
    int32_t representative = 0;  // index of the leaf node that represents this node

    // The representative light's own parameters, used to evaluate the cluster.
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    float range = 0.0f;  // 0: unbounded
    float spot_cos_inner = 1.0f;
    float spot_cos_outer = 0.0f;

    // Cluster attributes (SPEC §4).
    glm::vec3 intensity{0.0f};  // RGB cluster intensity: sum of leaves' color * intensity
    float brightness = 0.0f;    // scalar sum of leaves' intensity (Unreal's Brightness)
    float radius = kUnboundedRadius;  // influence radius around `position` (thesis rule)
    float falloff_exponent = 2.0f;    // inverse-square falloff
    glm::vec3 bbox_min{0.0f};  // bounds of the leaves' positions (directions for directional)
    glm::vec3 bbox_max{0.0f};
    glm::vec3 cone_axis{0.0f, 0.0f, -1.0f};  // orientation cone of spot lights
    // cos of its half-angle; -1 means all directions, the default of every node form: a
    // cone nobody computed then bounds as lights facing every way (loose, never too low).
    float cone_cos = -1.0f;
    // Joins trees of different light types, every light below indirect, or
    // every light below a radiosity patch (device/node_flags.h); the tree keeps
    // indirect lights and patches in subtrees of their own.
    NodeFlags flags;
    // The representative's disk radius when a patch (0 for every other light).
    float source_radius = 0.0f;

    bool is_leaf() const { return left == kNoChild && right == kNoChild; }
};

// 2^20 lights hold twice this each on the client: a new field goes in padding.
static_assert(sizeof(LightTreeNode) == 140);
// A node records the bounce its light does (kMaxRecordedBounce).
static_assert(std::is_same_v<decltype(LightTreeNode::bounce), decltype(SceneLight::bounce)>);

struct LightTree {
    // nodes[0] is the root when the tree is not empty. Nodes are in breadth-first
    // order from the root, so every child index is greater than its parent's.
    std::vector<LightTreeNode> nodes;
    uint32_t leaf_count = 0;

    bool empty() const { return nodes.empty(); }
};

}  // namespace lc
