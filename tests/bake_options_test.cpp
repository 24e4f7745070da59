// `bake --builder auto` (editor_client/commands/bake_options.h): the builder a
// scene's expected tree size picks (its lights and the server's), and the
// reason the report line gives.
#include <gtest/gtest.h>

#include <string>

#include "editor_client/commands/bake_options.h"
#include "protocol/bake_limits.h"

namespace lc::client {
namespace {

Scene scene_with(size_t lights, size_t classic = 0) {
    Scene scene;
    scene.lights.resize(lights + classic);
    for (size_t i = lights; i < lights + classic; ++i) scene.lights[i].classic = true;
    return scene;
}

TEST(AutoBuilder, PicksByTheTreesLightCount) {
    BakeFlags flags;
    std::string why;
    EXPECT_EQ(flags.resolved_builder(scene_with(kAutoBuilderLightLimit), &why), "optimal-pair");
    EXPECT_EQ(why, "auto: 131072 lights <= 131072");
    EXPECT_EQ(flags.resolved_builder(scene_with(kAutoBuilderLightLimit + 1), &why), "agglomerative");
    EXPECT_EQ(why, "auto: 131073 lights > 131072");
    EXPECT_EQ(flags.resolved_builder(scene_with(kAutoLbvhLightLimit), &why), "agglomerative");
    EXPECT_EQ(flags.resolved_builder(scene_with(kAutoLbvhLightLimit + 1), &why), "lbvh");
    EXPECT_EQ(why, "auto: 524289 lights > 524288");
    // Classic lights stay on the client: they do not count.
    EXPECT_EQ(flags.resolved_builder(scene_with(kAutoBuilderLightLimit, 1000)), "optimal-pair");
}

// The server makes lights too: the bake's tree is sized with them, so ten
// lamps with two million VPL paths bake by LBVH, not by optimal pairs.
TEST(AutoBuilder, CountsTheLightsTheServerMakes) {
    BakeFlags flags;
    std::string why;
    flags.indirect = "vpl";
    flags.indirect_request.vpl_count = 2'000'000;
    EXPECT_EQ(flags.resolved_builder(scene_with(10), &why), "lbvh");
    // Paths run until Russian roulette ends them: the reservation for two
    // million of them (twice the mean path length) is the server's cap.
    EXPECT_EQ(why, "auto: " + std::to_string(kMaxIndirectLights + 10) + " lights > 524288");
    flags.indirect_request.bounces = 3;
    flags.indirect_request.vpl_count = 100'000;
    EXPECT_EQ(flags.expected_tree_lights(scene_with(10)), 300'010u) << "one VPL a path and bounce at most";
    flags.indirect_request.vpl_count = uint64_t{1} << 30;
    EXPECT_EQ(flags.expected_tree_lights(scene_with(0)), kMaxIndirectLights) << "the server's cap";
    flags.indirect = "radiosity";
    EXPECT_EQ(flags.expected_tree_lights(scene_with(10)), 10u);

    Scene lit = scene_with(10);
    lit.materials.resize(2);
    lit.materials[1].emissive_factor = glm::vec3(0.0f, 2.0f, 0.0f);
    flags.area_lights = 200'000;
    EXPECT_EQ(flags.resolved_builder(lit, &why), "agglomerative") << "an emissive material's samples";
    EXPECT_EQ(why, "auto: 200010 lights > 131072");
    lit.materials[1].emissive_factor = glm::vec3(0.0f);
    EXPECT_EQ(flags.expected_tree_lights(lit), 10u);

    flags.environment.sky = "30,40,3";
    EXPECT_EQ(flags.expected_tree_lights(lit), 10u + kDefaultEnvironmentLights);
    flags.environment.lights = 600'000;
    EXPECT_EQ(flags.resolved_builder(lit), "lbvh");
}

TEST(AutoBuilder, AnExplicitBuilderIsKept) {
    BakeFlags flags;
    flags.builder = "agglomerative";
    std::string why = "unchanged";
    EXPECT_EQ(flags.resolved_builder(scene_with(2u << 20), &why), "agglomerative");
    EXPECT_EQ(why, "unchanged");
}

}  // namespace
}  // namespace lc::client
