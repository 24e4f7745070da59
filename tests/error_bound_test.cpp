// The per-node error bounds are conservative: over many random clusters and
// shading points, behind spot clusters, outside radii, and on trees from the
// server's builder.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <random>
#include <string_view>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/material_model.h"
#include "lightmass_server/builders/tree_builder.h"
#include "tree_fixtures.h"

namespace lc::test {
namespace {

// For a random cluster (one type, 1 to 8 lights) and a random shading point,
// normal and material (Lambert, or glossy seen from a random eye), the bound must be >= the exact sum over the cluster's lights and
// >= the cluster estimate, channel by channel.
TEST(ErrorBound, IsConservativeOverManyRandomConfigurations) {
    constexpr int kPointsPerCluster = 10;
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int checked = 0, nonzero = 0;
    for (int config = 0; config < 100000; ++config) {
        const LightType type = LightType(config % kLightTypeCount);
        const int count = 1 + int(rng() % 8);
        const float size = 0.01f + 3.0f * u(rng);
        const glm::vec3 center(8 * u(rng) - 4, 8 * u(rng) - 4, 4 * u(rng) - 1);
        std::vector<SceneLight> lights =
            random_lights_in_box(rng, count, type, center - size, center + size, config % 2 == 0);
        const bool has_cone = type == LightType::kSpot || type == LightType::kOriented;
        if (has_cone && config % 5 == 0) {
            // A tight cone of directions, where the exclusion test (spots) and
            // the emitter-cosine bound (oriented lights) matter.
            const glm::vec3 axis = lights[0].direction;
            for (SceneLight& l : lights)
                l.direction = glm::normalize(axis + 0.1f * glm::vec3(u(rng), u(rng), u(rng)));
        }
        const WalkTree tree = walk_tree(morton_pairing_tree(lights, uint64_t(config)));

        // Ten shading points per cluster: 10^6 (cluster, point) cases in all.
        for (int point = 0; point < kPointsPerCluster; ++point) {
        glm::dvec3 position(10 * u(rng) - 5, 10 * u(rng) - 5, 6 * u(rng) - 2);
        if ((config + point) % 7 == 0) position = glm::dvec3(lights[0].position);  // on a light
        if ((config + point) % 11 == 0)
            position = glm::dvec3(center) + 1e-3 * glm::dvec3(u(rng), u(rng), u(rng));
        glm::dvec3 normal(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
        if (glm::length(normal) < 1e-3) normal = {0, 0, 1};
        if ((config + point) % 13 == 0) {
            // Grazing: the normal perpendicular to the direction to a light.
            const glm::dvec3 to = glm::dvec3(lights[0].position) - position;
            if (glm::length(to) > 1e-6) normal = glm::cross(to, glm::dvec3(0.3, 0.7, 0.1));
            if (glm::length(normal) < 1e-9) normal = {0, 0, 1};
        }
        SurfacePoint p = surface(position, normal, {u(rng), u(rng), u(rng)});
        if ((config + point) % 2 == 0) {
            // Half the points are glossy (material_model.h), seen from a random eye.
            const shading::SurfaceMaterial m = shading::surface_material(
                {u(rng), u(rng), u(rng)}, u(rng), 0.1 + 0.9 * double(u(rng)));
            p.albedo = m.diffuse;
            p.specular = m.specular;
            p.exponent = m.exponent;
            const glm::dvec3 eye(10 * u(rng) - 5, 10 * u(rng) - 5, 6 * u(rng) - 2);
            p.mirror = shading::mirror_direction(p.normal, p.position, eye);
        }

        const glm::dvec3 bound = node_contribution_bound(tree, 0, p);
        const glm::dvec3 exact = shade_reference(lights, p);
        const glm::dvec3 estimate = shade_node(tree, 0, p);
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(bound[c]));
            // Lights and nodes store spot cosines at different precisions: 1e-6.
            ASSERT_GE(bound[c] * (1.0 + 1e-6) + 1e-300, exact[c])
                << "config " << config << " type " << int(type) << " channel " << c;
            ASSERT_GE(bound[c] * (1.0 + 1e-6) + 1e-300, estimate[c]) << "config " << config;
        }
        ++checked;
        if (bound.x > 0.0) ++nonzero;
        }
    }
    EXPECT_EQ(checked, 100000 * kPointsPerCluster);
    EXPECT_GT(nonzero, 100000);  // the test exercised real bounds, not only zeros
}

// The oriented bound (the emitter cosine's maximum over the box and the cone
// of normals) is zero behind a panel, and tighter than the point light's
// beside it, where the emitters' cosines are small.
TEST(ErrorBound, OrientedClusterBoundFollowsTheEmittersCosine) {
    std::vector<SceneLight> panel;
    for (int i = 0; i < 16; ++i) {
        SceneLight s = make_light(LightType::kOriented, {float(i % 4) * 0.1f, float(i / 4) * 0.1f, 5},
                                  1.0f, glm::vec3(1), 0.0f);
        s.direction = {0, 0, -1};
        s.guid = Guid{4, 4, 4, uint32_t(i + 1)};
        panel.push_back(s);
    }
    const WalkTree tree = walk_tree(morton_pairing_tree(panel, 1));
    EXPECT_EQ(node_contribution_bound(tree, 0, surface({0, 0, 10}, {0, 0, -1})), glm::dvec3(0.0));
    EXPECT_GT(node_contribution_bound(tree, 0, surface({0, 0, 0})).x, 0.0);
    // Far to the side, seen from a wall facing the panel: the emitter cosine
    // is about 0.5 / 20 = 0.025.
    const SurfacePoint side = surface({20, 0, 4.5}, {-1, 0, 0});
    std::vector<SceneLight> as_points = panel;
    for (SceneLight& l : as_points) l.type = LightType::kPoint;
    const double oriented = node_contribution_bound(tree, 0, side).x;
    const double point = node_contribution_bound(walk_tree(morton_pairing_tree(as_points, 1)), 0, side).x;
    EXPECT_GE(oriented, shade_reference(panel, side).x);
    EXPECT_LT(oriented, 0.1 * point);
}

TEST(ErrorBound, IsZeroBehindASpotClusterAndOutsideTheRadius) {
    std::vector<SceneLight> spots;
    for (int i = 0; i < 4; ++i) {
        SceneLight s =
            make_light(LightType::kSpot, {float(i) * 0.1f, 0, 5}, 10.0f, glm::vec3(1), 0.0f);
        s.direction = {0, 0, -1};
        s.inner_cone_angle = 0.1f;
        s.outer_cone_angle = 0.5f;
        spots.push_back(s);
    }
    const WalkTree tree = walk_tree(morton_pairing_tree(spots, 1));
    // Above the spots, which all shine down: no light can arrive.
    const SurfacePoint above = surface({0, 0, 10}, {0, 0, -1});
    EXPECT_EQ(node_contribution_bound(tree, 0, above), glm::dvec3(0.0));
    EXPECT_EQ(shade_reference(spots, above), glm::dvec3(0.0));
    // Below them: positive.
    EXPECT_GT(node_contribution_bound(tree, 0, surface({0, 0, 0})).x, 0.0);

    std::vector<SceneLight> ranged{
        make_light(LightType::kPoint, {0, 0, 1}, 1.0f, glm::vec3(1), 2.0f),
        make_light(LightType::kPoint, {1, 0, 1}, 1.0f, glm::vec3(1), 2.0f)};
    const WalkTree small = walk_tree(morton_pairing_tree(ranged, 1));
    EXPECT_EQ(node_contribution_bound(small, 0, surface({10, 0, 0})), glm::dvec3(0.0));
}

// The bounds must also hold on trees from the real builder (its radii, boxes
// and cones are what the renderer will see).
TEST(ErrorBound, HoldsOnTreesFromTheServerBuilder) {
    std::mt19937_64 rng(99);
    std::vector<SceneLight> lights = mixed_scene(rng);
    for (size_t i = 0; i < lights.size(); ++i) lights[i].guid = Guid{9, 9, 9, uint32_t(i + 1)};
    bake::BuildOptions options;
    options.seed = 4;
    Result<bake::BuildResult> built =
        bake::build_light_tree(lights, options, [](std::string_view, double) { return true; });
    ASSERT_TRUE(built.ok()) << built.error();
    ASSERT_EQ(built->tree.leaf_count, lights.size());
    const WalkTree tree = walk_tree(built->tree);
    std::uniform_real_distribution<double> u(-7, 7);
    for (int k = 0; k < 300; ++k) {
        const SurfacePoint p =
            surface({u(rng), u(rng), u(rng) * 0.3}, {u(rng), u(rng), u(rng) + 0.01});
        // Exact sum per subtree, bottom-up (children come after parents).
        std::vector<glm::dvec3> exact(tree.nodes.size(), glm::dvec3(0.0));
        for (size_t i = tree.nodes.size(); i-- > 0;) {
            int32_t children[2];
            const int count = children_of(tree, int32_t(i), children);
            if (count == 0) exact[i] = shade_node(tree, int32_t(i), p);
            for (int c = 0; c < count; ++c) exact[i] += exact[size_t(children[c])];
        }
        for (size_t i = 0; i < tree.nodes.size(); ++i) {
            if (joins_types(tree.nodes[i])) continue;
            const glm::dvec3 bound = node_contribution_bound(tree, int32_t(i), p);
            for (int c = 0; c < 3; ++c) {
                ASSERT_GE(bound[c] * (1.0 + 1e-5) + 1e-300, exact[i][c]) << "node " << i;
            }
        }
        expect_near_rel(shade_lightcuts(tree, {}, p, {CutCriterion::kBound, 0.0, 100000}).radiance,
                        shade_reference(lights, p), 1e-5, 1e-12);
    }
}

}  // namespace
}  // namespace lc::test
