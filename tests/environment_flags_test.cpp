// The environment flags of bake, render and view: a sky or a map loads, and a
// zero or absurd light budget, a budget without an environment, a bad --sky or
// a missing file is refused naming the problem.
#include <gtest/gtest.h>

#include "editor_client/commands/environment_flags.h"

namespace lc::client {
namespace {

std::string refusal(const EnvironmentFlags& flags) {
    auto loaded = flags.load();
    return loaded ? std::string("accepted") : loaded.error();
}

TEST(EnvironmentFlags, NothingRequestedIsNoEnvironment) {
    auto loaded = EnvironmentFlags{}.load();
    ASSERT_TRUE(loaded) << loaded.error();
    EXPECT_EQ(loaded.value(), nullptr);
}

TEST(EnvironmentFlags, SkyLoadsWithItsScale) {
    EnvironmentFlags flags;
    flags.sky = "25,100,4";
    flags.intensity = 0.5f;
    flags.lights = 64;
    auto loaded = flags.load();
    ASSERT_TRUE(loaded) << loaded.error();
    ASSERT_TRUE(loaded.value()->has_sky());
    EXPECT_EQ(*loaded.value()->sky, (SkyParameters{25.0f, 100.0f, 4.0f}));
    EXPECT_EQ(loaded.value()->intensity, 0.5f);
}

TEST(EnvironmentFlags, RefusesZeroAbsurdOrOrphanBudgets) {
    EnvironmentFlags flags;
    flags.sky = "25,100,4";
    flags.lights = 0;
    EXPECT_NE(refusal(flags).find("--environment lights: 0 is outside [2, 4194304]"), std::string::npos)
        << refusal(flags);
    flags.lights = kMaxEnvironmentLights + 1;
    EXPECT_NE(refusal(flags).find("4194305"), std::string::npos);
    EnvironmentFlags orphan;
    orphan.lights = 100;
    EXPECT_NE(refusal(orphan).find("needs --environment or --sky"), std::string::npos);
}

TEST(EnvironmentFlags, RefusesBadSkiesScalesAndFiles) {
    EnvironmentFlags sky;
    sky.sky = "25,100";
    EXPECT_NE(refusal(sky).find("ELEVATION,AZIMUTH,TURBIDITY"), std::string::npos);
    sky.sky = "25,100,4";
    sky.intensity = -1.0f;
    EXPECT_NE(refusal(sky).find("intensity"), std::string::npos);
    EnvironmentFlags file;
    file.file = "/nonexistent/studio.hdr";
    EXPECT_NE(refusal(file).find("no such file"), std::string::npos);
}

}  // namespace
}  // namespace lc::client
