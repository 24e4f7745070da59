// The lights a radiosity patch leaves: patches at a contact (a floor at the
// foot of a wall) split into 16 lights over their area, the others one light
// at their centre, the power the same either way.
#include "lightmass_server/indirect/patch_lights.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "indirect_scenes.h"

namespace lc::bake {
namespace {

// A 2x2 floor at y = 0 facing +y with a wall standing on its x = 2 edge, facing -x.
SceneGeometry floor_and_wall() {
    SceneGeometry g;
    g.materials.push_back(test::reflecting(0.5f, 0.0f));
    test::add_quad(g, glm::vec3(0.0f), glm::vec3(0, 0, 2), glm::vec3(2, 0, 0), 0);
    test::add_quad(g, glm::vec3(2, 0, 0), glm::vec3(0, 0, 2), glm::vec3(0, 2, 0), 0);
    return g;
}

Patch floor_patch(float x, float z, float size) {
    Patch p;
    p.vertices[0] = {x, 0.0f, z};
    p.vertices[1] = {x, 0.0f, z + size};
    p.vertices[2] = {x + size, 0.0f, z};
    p.centre = (p.vertices[0] + p.vertices[1] + p.vertices[2]) / 3.0f;
    p.normal = {0.0f, 1.0f, 0.0f};
    p.area = 0.5f * size * size;
    return p;
}

TEST(PatchLights, AFloorPatchAtTheFootOfAWallIsNearAContactAndOneInTheOpenIsNot) {
    const SceneGeometry g = floor_and_wall();
    auto caster = RayCaster::build(g, 1);
    ASSERT_TRUE(caster.ok()) << caster.error();
    const float epsilon = 1e-4f;
    EXPECT_TRUE(near_contact(floor_patch(1.75f, 1.0f, 0.25f), *caster, epsilon));
    EXPECT_FALSE(near_contact(floor_patch(0.5f, 1.0f, 0.25f), *caster, epsilon));
    // The wall's own patches see the floor at their foot.
    Patch wall;
    wall.vertices[0] = {2.0f, 0.0f, 1.0f};
    wall.vertices[1] = {2.0f, 0.25f, 1.0f};
    wall.vertices[2] = {2.0f, 0.0f, 1.25f};
    wall.centre = (wall.vertices[0] + wall.vertices[1] + wall.vertices[2]) / 3.0f;
    wall.normal = {-1.0f, 0.0f, 0.0f};
    wall.area = 0.5f * 0.25f * 0.25f;
    EXPECT_TRUE(near_contact(wall, *caster, epsilon));
}

TEST(PatchLights, SubdividedLightsKeepThePowerAndLieOnThePatch) {
    const Patch p = floor_patch(0.0f, 0.0f, 0.5f);
    const glm::dvec3 reflected(2.0, 1.0, 0.5);
    std::vector<IndirectLight> one, sixteen;
    append_patch_lights(p, reflected, 1e-3f, 0, one);
    append_patch_lights(p, reflected, 1e-3f, 2, sixteen);
    ASSERT_EQ(one.size(), 1u);
    ASSERT_EQ(sixteen.size(), 16u);
    EXPECT_FLOAT_EQ(one[0].power.x, float(2.0 * double(p.area)));
    EXPECT_NEAR(one[0].position.y, 1e-3f, 1e-7f);
    EXPECT_FLOAT_EQ(one[0].patch_radius, equivalent_disk_radius(p.area));
    glm::dvec3 total(0.0);
    for (const IndirectLight& l : sixteen) {
        total += glm::dvec3(l.power);
        EXPECT_FLOAT_EQ(l.patch_radius, equivalent_disk_radius(p.area / 16.0f));
        EXPECT_EQ(l.normal, p.normal);
        // Inside the patch: x, z >= 0 and x + z <= its size.
        EXPECT_GE(l.position.x, 0.0f);
        EXPECT_GE(l.position.z, 0.0f);
        EXPECT_LE(l.position.x + l.position.z, 0.5f);
    }
    EXPECT_NEAR(total.x, double(one[0].power.x), 1e-5);
    EXPECT_NEAR(total.z, double(one[0].power.z), 1e-5);
    // The light nearest the x = 0 edge sits a twelfth of the size from it (one light: a sixth).
    float lowest = 1.0f;
    for (const IndirectLight& l : sixteen) lowest = std::min(lowest, l.position.x);
    EXPECT_NEAR(lowest, 0.5f / 12.0f, 1e-5f);
}

}  // namespace
}  // namespace lc::bake
