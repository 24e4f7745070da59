#pragma once
// Shared by the light-tree builder tests: random scenes, and the invariants
// every built tree must satisfy, checked both on the double-precision build
// and on the exported float tree.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "lightcuts/tree/build_tree.h"
#include "lightmass_server/builders/cluster_attributes.h"
#include "lightcuts/tree/light_tree.h"
#include "lightcuts/scene_light.h"

namespace lc::test {

inline Guid light_guid(uint32_t index) {
    return Guid{0x4C494748u, 0x54000000u, 0u, index + 1};
}

// Lights of one type, uniformly in a cube of side `extent`, with random
// colours, intensities in [0.5, 2) and ranges in [1, 4) x extent / 10.
inline std::vector<SceneLight> random_lights(uint32_t count, uint64_t seed, LightType type,
                                             float extent = 100.0f) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<SceneLight> lights(count);
    for (uint32_t i = 0; i < count; ++i) {
        SceneLight& light = lights[i];
        light.guid = light_guid(i);
        light.type = type;
        light.position = glm::vec3(unit(rng), unit(rng), unit(rng)) * extent;
        glm::vec3 d(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
        if (glm::length(d) < 1e-3f) d = glm::vec3(0.0f, 0.0f, -1.0f);
        light.direction = glm::normalize(d);
        light.color = glm::vec3(0.2f + unit(rng), 0.2f + unit(rng), 0.2f + unit(rng));
        light.intensity = 0.5f + 1.5f * unit(rng);
        light.range = type == LightType::kDirectional ? 0.0f : extent * (0.1f + 0.3f * unit(rng));
        light.inner_cone_angle = 0.2f;
        light.outer_cone_angle = 0.6f;
    }
    return lights;
}

inline bool finite_vec(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The arena with one leaf per light, as build_light_tree makes it.
inline lc::BuildArena leaf_arena(std::span<const SceneLight> lights) {
    lc::BuildArena arena;
    arena.lights = lights;
    arena.nodes.reserve(2 * lights.size() + 3);
    for (uint32_t i = 0; i < lights.size(); ++i)
        arena.nodes.push_back(make_leaf(lights[i], i));
    return arena;
}

inline std::vector<uint32_t> all_indices(size_t count) {
    std::vector<uint32_t> ids(count);
    for (uint32_t i = 0; i < count; ++i) ids[i] = i;
    return ids;
}

// Double-precision invariants of the subtree at `root`: every leaf reached once,
// root intensity = sum of leaves (1e-9 relative), bboxes hold their leaves,
// cones hold their leaves' directions, radius encloses every leaf's sphere
// (exhaustively when small, else by the local rule, which implies it), and the
// representative is a leaf of the subtree.
inline void expect_build_invariants(const lc::BuildArena& arena, int32_t root,
                                    std::span<const uint32_t> leaves) {
    ASSERT_GE(root, 0);
    const auto& nodes = arena.nodes;
    // Euler-tour intervals (iterative) for "x is in the subtree of y".
    std::vector<uint32_t> tin(nodes.size(), UINT32_MAX), tout(nodes.size(), 0);
    std::vector<std::pair<uint32_t, bool>> stack{{uint32_t(root), false}};
    std::vector<uint32_t> post_order;
    uint32_t clock = 0;
    while (!stack.empty()) {
        auto [id, done] = stack.back();
        stack.pop_back();
        if (done) {
            tout[id] = clock;
            post_order.push_back(id);
            continue;
        }
        ASSERT_EQ(tin[id], UINT32_MAX) << "node " << id << " reached twice";
        tin[id] = clock++;
        stack.emplace_back(id, true);
        if (nodes[id].right >= 0) stack.emplace_back(uint32_t(nodes[id].right), false);
        if (nodes[id].left >= 0) stack.emplace_back(uint32_t(nodes[id].left), false);
    }
    for (uint32_t leaf : leaves) ASSERT_NE(tin[leaf], UINT32_MAX) << "leaf " << leaf << " missing";

    glm::dvec3 leaf_sum(0.0);
    for (uint32_t leaf : leaves) leaf_sum += nodes[leaf].intensity;
    const glm::dvec3 root_sum = nodes[size_t(root)].intensity;
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(root_sum[c], leaf_sum[c], 1e-9 * std::max(1e-300, std::abs(leaf_sum[c])));
    }

    const bool exhaustive = leaves.size() <= 1500;
    for (uint32_t id : post_order) {
        const lc::BuildNode& node = nodes[id];
        EXPECT_TRUE(std::isfinite(node.brightness) && std::isfinite(node.radius));
        const uint32_t rep = node.representative;
        ASSERT_TRUE(nodes[rep].is_leaf()) << "representative of " << id << " is no leaf";
        ASSERT_TRUE(tin[id] <= tin[rep] && tin[rep] < tout[id])
            << "representative of " << id << " outside its subtree";
        if (node.is_leaf() || node.flags.mixed_types()) continue;
        const lc::BuildNode& l = nodes[size_t(node.left)];
        const lc::BuildNode& r = nodes[size_t(node.right)];
        EXPECT_LT(l.min_light_index, r.min_light_index) << "left child must hold the first light";
        EXPECT_EQ(node.guid, Guid::combine(l.guid, r.guid));
        EXPECT_TRUE(rep == l.representative || rep == r.representative);
        // Local radius rule (the thesis's); with leaves' radii it implies enclosure.
        const glm::dvec3 p(arena.lights[rep].position);
        if (l.unbounded() || r.unbounded()) {
            EXPECT_TRUE(node.unbounded());
        } else {
            for (const lc::BuildNode* child : {&l, &r}) {
                const glm::dvec3 c(arena.lights[child->representative].position);
                EXPECT_GE(node.radius * (1 + 1e-12), glm::distance(p, c) + child->radius);
            }
        }
    }

    // Per leaf: walk up by brute force in small trees (O(n * depth)).
    if (!exhaustive) return;
    std::vector<int32_t> parent(nodes.size(), -1);
    for (uint32_t id : post_order) {
        if (nodes[id].left >= 0) parent[size_t(nodes[id].left)] = int32_t(id);
        if (nodes[id].right >= 0) parent[size_t(nodes[id].right)] = int32_t(id);
    }
    for (uint32_t leaf : leaves) {
        const lc::BuildNode& l = nodes[leaf];
        const glm::dvec3 point = l.bbox_min;
        for (int32_t a = parent[leaf]; a >= 0; a = parent[size_t(a)]) {
            const lc::BuildNode& node = nodes[size_t(a)];
            for (int c = 0; c < 3; ++c) {
                EXPECT_LE(node.bbox_min[c], point[c]);
                EXPECT_GE(node.bbox_max[c], point[c]);
            }
            if (node.flags.mixed_types()) continue;
            if (!node.unbounded()) {
                const glm::dvec3 p(arena.lights[node.representative].position);
                const glm::dvec3 q(arena.lights[leaf].position);
                EXPECT_GE(node.radius * (1 + 1e-12) + 1e-9, glm::distance(p, q) + l.radius);
            }
            if (l.cone_cos > -1.0 && node.cone_cos > -1.0) {
                EXPECT_GE(glm::dot(node.cone_axis, l.cone_axis), node.cone_cos - 1e-9)
                    << "cone of " << a << " misses leaf " << leaf;
            }
        }
    }
}

// Float-tree invariants: breadth-first indices, finite values, leaf count,
// conservative bounds, representative a leaf of the subtree.
inline void expect_tree_invariants(const LightTree& tree, std::span<const SceneLight> lights) {
    ASSERT_EQ(tree.leaf_count, lights.size());
    if (lights.empty()) {
        EXPECT_TRUE(tree.empty());
        return;
    }
    ASSERT_EQ(tree.nodes.size(), 2 * lights.size() - 1);  // binary merges, junctions included
    const size_t n = tree.nodes.size();
    std::vector<int32_t> parent(n, -1);
    for (size_t i = 0; i < n; ++i) {
        const LightTreeNode& node = tree.nodes[i];
        EXPECT_TRUE(finite_vec(node.intensity) && finite_vec(node.bbox_min) &&
                    finite_vec(node.bbox_max) && finite_vec(node.cone_axis) &&
                    std::isfinite(node.brightness) && std::isfinite(node.radius) &&
                    std::isfinite(node.cone_cos))
            << "node " << i << " has a non-finite value";
        if (node.is_leaf()) continue;
        ASSERT_GT(node.left, int32_t(i));
        ASSERT_GT(node.right, int32_t(i));
        ASSERT_LT(size_t(node.right), n);
        parent[size_t(node.left)] = int32_t(i);
        parent[size_t(node.right)] = int32_t(i);
    }
    // Leaves carry their light's GUID; each light appears once.
    std::vector<Guid> leaf_guids, light_guids;
    for (const LightTreeNode& node : tree.nodes) {
        if (node.is_leaf()) leaf_guids.push_back(node.guid);
    }
    for (const SceneLight& light : lights) light_guids.push_back(light.guid);
    std::sort(leaf_guids.begin(), leaf_guids.end());
    std::sort(light_guids.begin(), light_guids.end());
    EXPECT_EQ(leaf_guids, light_guids);

    for (size_t i = 0; i < n; ++i) {
        const LightTreeNode& node = tree.nodes[i];
        const size_t rep = size_t(node.representative);
        ASSERT_LT(rep, n);
        ASSERT_TRUE(tree.nodes[rep].is_leaf());
        int32_t up = int32_t(rep);
        while (up >= 0 && up != int32_t(i)) up = parent[size_t(up)];
        ASSERT_EQ(up, int32_t(i)) << "representative of node " << i << " outside its subtree";
        EXPECT_EQ(node.position, tree.nodes[rep].position);
        if (!node.is_leaf()) continue;
        // Every ancestor's float box holds the leaf's point.
        const glm::vec3 point =
            node.type == LightType::kDirectional ? node.direction : node.position;
        for (int32_t a = parent[i]; a >= 0; a = parent[size_t(a)]) {
            const LightTreeNode& anc = tree.nodes[size_t(a)];
            for (int c = 0; c < 3; ++c) {
                EXPECT_LE(anc.bbox_min[c], point[c]);
                EXPECT_GE(anc.bbox_max[c], point[c]);
            }
            if (n > 3000) break;  // deep chains: the parent check suffices
        }
    }
}

}  // namespace lc::test
