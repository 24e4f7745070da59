// `bake --builder auto` (editor_client/commands/bake_options.h): the builder a
// scene's size picks, and the reason the report line gives.
#include <gtest/gtest.h>

#include <string>

#include "editor_client/commands/bake_options.h"

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

TEST(AutoBuilder, AnExplicitBuilderIsKept) {
    BakeFlags flags;
    flags.builder = "agglomerative";
    std::string why = "unchanged";
    EXPECT_EQ(flags.resolved_builder(scene_with(2u << 20), &why), "agglomerative");
    EXPECT_EQ(why, "unchanged");
}

}  // namespace
}  // namespace lc::client
