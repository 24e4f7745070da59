// make-scene cornell-emissive: the Cornell box lit only by its ceiling panel
// (published reflectances, no punctual light). Its geometry goes to the bake,
// which turns the panel into oriented lights carrying the panel's power.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "editor_client/scene/scene_generator.h"
#include "editor_client/scene/surface_geometry.h"
#include "lightmass_server/mpi/bake_dispatch.h"

namespace lc::client {
namespace {

TEST(CornellEmissive, IsLitOnlyByItsPanelWithThePublishedReflectances) {
    Result<Scene> scene = make_named_scene("cornell-emissive");
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_TRUE(scene->lights.empty());
    std::vector<glm::vec3> albedos;
    for (const Material& m : scene->materials) albedos.push_back(glm::vec3(m.base_color_factor));
    for (const glm::vec3& published : {kCornellWhite, kCornellRed, kCornellGreen})
        EXPECT_NE(std::find(albedos.begin(), albedos.end(), published), albedos.end());

    std::shared_ptr<const SceneGeometry> geometry = geometry_the_bake_needs(*scene);
    ASSERT_NE(geometry, nullptr);
    EXPECT_EQ(emissive_triangle_count(*geometry), 2u);
    glm::dvec3 power(0.0);
    for (const SurfaceTriangle& t : geometry->triangles)
        power += std::numbers::pi * double(triangle_area(t)) *
                 glm::dvec3(geometry->materials[t.material].emission);
    const double side_x = kCornellSize * 130.0 / 555.0, side_z = kCornellSize * 105.0 / 555.0;
    EXPECT_NEAR(power.x, std::numbers::pi * 17.0 * side_x * side_z, 1e-5 * power.x);

    bake::BakeInputs inputs;
    inputs.lights = std::make_shared<const std::vector<SceneLight>>(scene->lights);
    inputs.geometry = geometry;
    inputs.build.builder = BuilderKind::kAgglomerative;
    Result<bake::BuildResult> built = bake::run_bake(inputs, nullptr);
    ASSERT_TRUE(built.ok()) << built.error();
    EXPECT_EQ(built->tree.leaf_count, kDefaultAreaLights);
    // The root carries the panel's power as the leaves' intensity: pi I = P.
    const glm::dvec3 root(built->tree.nodes[0].intensity);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(std::numbers::pi * root[c], power[c], 1e-5 * power[c]);
    for (const LightTreeNode& node : built->tree.nodes) {
        if (!node.is_leaf()) continue;
        EXPECT_EQ(node.type, LightType::kOriented);
        EXPECT_EQ(node.direction, glm::vec3(0, -1, 0));  // the panel faces the floor
    }
}

}  // namespace
}  // namespace lc::client
