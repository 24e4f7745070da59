// The render's census line for bounced light (editor_client/render/analysis/indirect_census.h).
#include <gtest/gtest.h>

#include "editor_client/render/analysis/indirect_census.h"

namespace lc::client {
namespace {

IndirectCensusFacts with_tree() {
    IndirectCensusFacts f;
    f.has_tree = true;
    f.scene_has_geometry = true;
    return f;
}

IndirectRequest request(IndirectMethod method, uint32_t bounces) {
    IndirectRequest r;
    r.method = method;
    r.bounces = bounces;
    return r;
}

TEST(IndirectCensus, NothingWithoutATree) {
    EXPECT_EQ(indirect_census(IndirectCensusFacts{}), "");
}

TEST(IndirectCensus, VplsWithTheBakesBounces) {
    IndirectCensusFacts f = with_tree();
    f.vpls = 32609;
    f.clamped_fraction = 0.0178;
    f.baked = request(IndirectMethod::kVpl, 4);
    EXPECT_EQ(indirect_census(f), "simulated (32609 VPLs, 4 bounces, clamped energy 1.78%)");
}

TEST(IndirectCensus, ATreeFromADumpDoesNotKnowItsBounces) {
    IndirectCensusFacts f = with_tree();
    f.vpls = 1;
    EXPECT_EQ(
        indirect_census(f),
        "simulated (1 VPL, bounces not recorded in the tree (an older server), see the bake's census, "
        "clamped energy 0%)");
}

TEST(IndirectCensus, PatchesHoldEveryBounce) {
    IndirectCensusFacts f = with_tree();
    f.patches = 1290;
    f.clamped_fraction = 0.001;
    EXPECT_EQ(indirect_census(f), "simulated (1290 patches, all bounces, clamped energy 0.1%)");
}

TEST(IndirectCensus, LeftOut) {
    IndirectCensusFacts f = with_tree();
    f.patches = 2;
    f.left_out = true;
    EXPECT_EQ(indirect_census(f), "skipped (--indirect off: 2 patches of the tree left out)");
}

TEST(IndirectCensus, SkippedSaysWhy) {
    IndirectCensusFacts f = with_tree();
    EXPECT_EQ(indirect_census(f),
              "skipped: the tree holds no indirect light (bake --indirect vpl|radiosity)");
    f.baked = request(IndirectMethod::kOff, 1);
    EXPECT_EQ(indirect_census(f), "skipped: no bounce requested");
    f.baked = request(IndirectMethod::kVpl, 0);
    EXPECT_EQ(indirect_census(f), "skipped: no bounce requested");
    f.baked = request(IndirectMethod::kRadiosity, 1);
    f.scene_has_geometry = false;
    EXPECT_EQ(indirect_census(f), "skipped: the scene has no geometry");
    f.scene_has_geometry = true;
    EXPECT_EQ(indirect_census(f),
              "skipped: the bake made no indirect light (no surface reflects the scene's light)");
}

}  // namespace
}  // namespace lc::client
