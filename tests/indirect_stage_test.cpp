// The bake's indirect stage: its census line for each outcome, the solver
// it dispatches to, and the radiosity PLY written for inspection.
#include "lightmass_server/indirect/indirect_stage.h"

#include <gtest/gtest.h>

#include <sstream>

#include "indirect_scenes.h"
#include "lightmass_server/indirect/radiosity_ply.h"

namespace lc::bake {
namespace {

TEST(IndirectStage, SaysWhyItSkips) {
    SceneGeometry box = test::closed_box({glm::vec3(0.5f), glm::vec3(1.0f)});
    auto caster = RayCaster::build(box, 1);
    ASSERT_TRUE(caster.ok());
    IndirectOptions off;
    auto skipped = run_indirect_stage(box, &*caster, {}, off, {});
    ASSERT_TRUE(skipped.ok());
    EXPECT_EQ(skipped->census, "skipped: no bounce requested");
    EXPECT_TRUE(skipped->lights.empty());

    IndirectOptions zero_bounces;
    zero_bounces.method = IndirectMethod::kVpl;
    zero_bounces.vpl.bounces = 0;
    EXPECT_EQ(run_indirect_stage(box, &*caster, {}, zero_bounces, {})->census, "skipped: no bounce requested");

    IndirectOptions vpl;
    vpl.method = IndirectMethod::kVpl;
    SceneGeometry empty;
    auto no_geometry = run_indirect_stage(empty, nullptr, {}, vpl, {});
    ASSERT_TRUE(no_geometry.ok());
    EXPECT_EQ(no_geometry->census, "skipped: the scene has no geometry");
}

TEST(IndirectStage, CountsWhatItSimulated) {
    SceneGeometry box = test::closed_box({glm::vec3(0.5f), glm::vec3(1.0f)});
    auto caster = RayCaster::build(box, 1);
    ASSERT_TRUE(caster.ok());
    IndirectOptions vpl;
    vpl.method = IndirectMethod::kVpl;
    vpl.vpl.particle_count = 1000;
    vpl.vpl.bounces = 1;
    auto traced = run_indirect_stage(box, &*caster, {}, vpl, {});
    ASSERT_TRUE(traced.ok());
    EXPECT_EQ(traced->census, "simulated (1000 VPLs from 1000 particles, 1 bounces)");
    EXPECT_EQ(traced->lights.size(), 1000u);

    IndirectOptions radiosity;
    radiosity.method = IndirectMethod::kRadiosity;
    radiosity.radiosity.patch_size = 2.0f;
    radiosity.radiosity.max_steps = 5;
    auto solved = run_indirect_stage(box, &*caster, {}, radiosity, {});
    ASSERT_TRUE(solved.ok());
    EXPECT_EQ(solved->census.rfind("simulated (12 patches, all bounces, 5 steps, ", 0), 0u) << solved->census;
    ASSERT_EQ(solved->warnings.size(), 1u);
    EXPECT_EQ(solved->patches.size(), 12u);
    // Every patch of a closed box touches another face: 16 lights each (patch_lights.h).
    EXPECT_EQ(solved->lights.size(), 12u * 16u);
}

TEST(RadiosityPly, WritesEveryPatchWithItsRadiosity) {
    Patch patch;
    patch.vertices[0] = {0, 0, 0};
    patch.vertices[1] = {1, 0, 0};
    patch.vertices[2] = {0, 1, 0};
    std::vector<Patch> patches = {patch, patch};
    std::vector<glm::vec3> radiosity = {{2.0f, 1.0f, 0.0f}, {0.5f, 0.5f, 0.5f}};
    std::string ply = radiosity_ply(patches, radiosity);
    EXPECT_NE(ply.find("element vertex 6\n"), std::string::npos);
    EXPECT_NE(ply.find("element face 2\n"), std::string::npos);
    // The brightest channel maps to 255, zero to 0.
    EXPECT_NE(ply.find("0 0 0 2 1 0 255 188 0\n"), std::string::npos) << ply;
    EXPECT_NE(ply.find("3 3 4 5\n"), std::string::npos);
    EXPECT_FALSE(write_radiosity_ply("/nonexistent-dir/r.ply", patches, radiosity).ok());
}

}  // namespace
}  // namespace lc::bake
