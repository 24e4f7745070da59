// The client's geometry for the bake (editor_client/scene/surface_geometry.h):
// every drawn triangle, emission from the factor (strength included) times
// the emissive texture's mean over the triangle, and no geometry at all when
// nothing emits, so such a bake sends what it always did.
#include <gtest/gtest.h>

#include "editor_client/scene/scene_generator.h"
#include "editor_client/scene/surface_geometry.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

TEST(SurfaceGeometry, NothingEmitsNothingIsSent) {
    const Scene room = make_room_scene();
    EXPECT_EQ(geometry_the_bake_needs(room), nullptr);
    const SceneGeometry g = extract_surface_geometry(room);
    EXPECT_EQ(g.triangles.size(), 12u);  // six quads
    EXPECT_FALSE(emits_power(g));
}

TEST(SurfaceGeometry, EmissiveTexturesAreReducedPerTriangle) {
    Scene scene;
    Material panel;
    panel.metallic = 0.0f;
    panel.emissive_factor = {4.0f, 2.0f, 1.0f};
    panel.emissive_texture = 0;
    scene.materials = {panel};
    // Left half white, right half black (sRGB 255 and 0 decode exactly).
    Texture texture;
    texture.width = 2;
    texture.height = 1;
    texture.rgba8 = {255, 255, 255, 255, 0, 0, 0, 255};
    scene.textures = {texture};
    // One quad, uv (0,0)-(1,1): its first triangle (0, 1, 2) covers u > v, its
    // second (0, 2, 3) u < v.
    scene.meshes.push_back(test::make_quad({0, 1, 0}, {1, 0, 0}, {0, 0, 1}, 0));
    const std::shared_ptr<const SceneGeometry> g = geometry_the_bake_needs(scene);
    ASSERT_NE(g, nullptr);
    ASSERT_EQ(g->triangles.size(), 2u);
    ASSERT_EQ(g->materials.size(), 2u);  // one per textured triangle
    const glm::vec3 e0 = g->materials[g->triangles[0].material].emission;
    const glm::vec3 e1 = g->materials[g->triangles[1].material].emission;
    // The white half's share of each triangle, from the 6 x 6 stratified points.
    EXPECT_GT(e1.x, e0.x);
    EXPECT_NEAR((e0.x + e1.x) / 2.0f, 2.0f, 0.25f);  // half the quad is white
    EXPECT_FLOAT_EQ(e0.y / e0.x, 0.5f);            // the factor's colour is kept
    EXPECT_EQ(g->triangles[0].normals[0], glm::vec3(0, -1, 0));
    EXPECT_EQ(emissive_triangle_count(*g), 2u);
}

}  // namespace
}  // namespace lc::client
