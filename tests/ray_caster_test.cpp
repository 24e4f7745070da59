// The server's Embree ray caster: hits, misses, occlusion, degenerate input,
// and a closed box that no ray from inside may escape.
#include "lightmass_server/raycast/ray_caster.h"

#include "indirect_scenes.h"

#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>

namespace lc {
namespace {

SurfaceTriangle triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) { return test::flat_triangle(a, b, c, 0); }

// The unit square at height y, facing down, as two triangles.
void add_ceiling(SceneGeometry& g, float y) {
    g.triangles.push_back(triangle({0, y, 0}, {1, y, 0}, {1, y, 1}));
    g.triangles.push_back(triangle({0, y, 0}, {1, y, 1}, {0, y, 1}));
}

TEST(RayCaster, HitsTheNearestTriangleAndReportsItsIndex) {
    SceneGeometry g;
    g.materials.push_back({});
    add_ceiling(g, 2.0f);
    add_ceiling(g, 1.0f);  // triangles 2 and 3 are nearer to the origin below
    auto caster = RayCaster::build(g, 1);
    ASSERT_TRUE(caster.ok()) << caster.error();
    auto hit = caster->intersect({0.75f, 0.0f, 0.25f}, {0, 1, 0}, 0.0f, 100.0f);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->distance, 1.0f, 1e-6f);
    EXPECT_EQ(hit->triangle, 2u);
    // Distances are in the direction's units.
    auto scaled = caster->intersect({0.75f, 0.0f, 0.25f}, {0, 2, 0}, 0.0f, 100.0f);
    ASSERT_TRUE(scaled.has_value());
    EXPECT_NEAR(scaled->distance, 0.5f, 1e-6f);
}

TEST(RayCaster, MissesAndRespectsTheSegment) {
    SceneGeometry g;
    g.materials.push_back({});
    add_ceiling(g, 1.0f);
    auto caster = RayCaster::build(g);
    ASSERT_TRUE(caster.ok());
    EXPECT_FALSE(caster->intersect({2, 0, 2}, {0, 1, 0}, 0.0f, 100.0f).has_value());
    EXPECT_FALSE(caster->intersect({0.5f, 0, 0.5f}, {0, -1, 0}, 0.0f, 100.0f).has_value());
    EXPECT_TRUE(caster->occluded({0.5f, 0, 0.5f}, {0, 1, 0}, 0.0f, 1.5f));
    EXPECT_FALSE(caster->occluded({0.5f, 0, 0.5f}, {0, 1, 0}, 0.0f, 0.9f));
    EXPECT_FALSE(caster->occluded({0.5f, 0, 0.5f}, {0, 1, 0}, 1.1f, 5.0f));
    EXPECT_FALSE(caster->occluded({0.5f, 0, 0.5f}, {0, 1, 0}, 1.0f, 1.0f));
}

TEST(RayCaster, SkipsDegenerateTrianglesAndKeepsIndices) {
    SceneGeometry g;
    g.materials.push_back({});
    g.triangles.push_back(triangle({0, 1, 0}, {1, 1, 0}, {1, 1, 1}));
    g.triangles[0].positions[2] = g.triangles[0].positions[1];  // zero area
    SurfaceTriangle nan_triangle = triangle({0, 1, 0}, {1, 1, 0}, {1, 1, 1});
    nan_triangle.positions[1].x = std::numeric_limits<float>::quiet_NaN();
    g.triangles.push_back(nan_triangle);
    add_ceiling(g, 1.0f);
    auto caster = RayCaster::build(g);
    ASSERT_TRUE(caster.ok());
    EXPECT_EQ(caster->skipped_degenerate(), 2u);
    EXPECT_EQ(caster->triangle_count(), 2u);
    auto hit = caster->intersect({0.75f, 0.0f, 0.25f}, {0, 1, 0}, 0.0f, 100.0f);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->triangle, 2u);
}

TEST(RayCaster, OnlyDegenerateTrianglesGiveACasterThatHitsNothing) {
    SceneGeometry g;
    g.materials.push_back({});
    g.triangles.push_back(triangle({0, 1, 0}, {1, 1, 0}, {1, 1, 1}));
    g.triangles[0].positions[1] = g.triangles[0].positions[0];
    auto caster = RayCaster::build(g);
    ASSERT_TRUE(caster.ok());
    EXPECT_EQ(caster->triangle_count(), 0u);
    EXPECT_FALSE(caster->intersect({0, 0, 0}, {0, 1, 0}, 0.0f, 100.0f).has_value());
    EXPECT_FALSE(caster->occluded({0, 0, 0}, {0, 1, 0}, 0.0f, 100.0f));
}

TEST(RayCaster, NoRayEscapesAClosedBox) {
    auto caster = RayCaster::build(test::closed_box(SurfaceMaterial{}));
    ASSERT_TRUE(caster.ok());
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::normal_distribution<float> gauss;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 origin(unit(rng), unit(rng), unit(rng));
        glm::vec3 dir(gauss(rng), gauss(rng), gauss(rng));
        if (glm::length(dir) < 1e-3f) continue;
        // Aim some rays exactly at edges and corners, where cracks would be.
        if (i % 4 == 0) dir = glm::vec3(float(i & 8 ? 1 : 0), 1.0f, float(i & 16 ? 1 : 0)) - origin;
        dir = glm::normalize(dir);
        auto hit = caster->intersect(origin, dir, 0.0f, 10.0f);
        ASSERT_TRUE(hit.has_value()) << "ray " << i << " escaped";
        EXPECT_LE(hit->distance, std::sqrt(3.0f) + 1e-4f);
        EXPECT_LT(hit->triangle, 12u);
    }
}

}  // namespace
}  // namespace lc
