// The BakeRequest limits both programs check (protocol/bake_limits.h,
// docs/PROTOCOL.md): each setting at its limit passes, one past it is
// refused with a message naming the setting, the value and the range.
#include "protocol/bake_limits.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace lc {
namespace {

BakeRequestMsg vpl(uint32_t bounces, uint64_t paths) {
    BakeRequestMsg request;
    request.indirect = {IndirectMethod::kVpl, bounces, paths, 0.25f, 0.01f};
    return request;
}

BakeRequestMsg radiosity(float patch_size, float tolerance) {
    BakeRequestMsg request;
    request.indirect = {IndirectMethod::kRadiosity, 1, 1, patch_size, tolerance};
    return request;
}

std::string refusal(const BakeRequestMsg& request) {
    Status status = validate_bake_settings(request);
    return status ? std::string() : status.error();
}

TEST(BakeLimits, ReadableNumbersUseTheShortestForm) {
    EXPECT_EQ(readable_number(1e-37), "1e-37");
    EXPECT_EQ(readable_number(0.25), "0.25");
    EXPECT_EQ(readable_number(1e6), "1e+06");
}

TEST(BakeLimits, DefaultsAndLimitsPass) {
    EXPECT_TRUE(validate_bake_settings(BakeRequestMsg{}));
    EXPECT_TRUE(validate_bake_settings(vpl(kMaxBakeBounces, kMaxVplPaths)));
    EXPECT_TRUE(validate_bake_settings(vpl(1, 1)));
    EXPECT_TRUE(validate_bake_settings(radiosity(kMinPatchSize, 0.0f)));
    EXPECT_TRUE(validate_bake_settings(radiosity(kMaxPatchSize, 0.999f)));
    BakeRequestMsg counts;
    counts.area_lights = kMaxAreaLights;
    counts.environment_lights = kMaxBakeEnvironmentLights;
    EXPECT_TRUE(validate_bake_settings(counts));
}

TEST(BakeLimits, EachSettingPastItsLimitIsNamed) {
    EXPECT_NE(refusal(vpl(0, 100)).find("vpl bounces 0"), std::string::npos);
    EXPECT_NE(refusal(vpl(kMaxBakeBounces + 1, 100)).find("1 to 65535"), std::string::npos);
    EXPECT_NE(refusal(vpl(1, 1000000000000ull)).find("vpl count (light paths) 1000000000000"),
              std::string::npos);
    EXPECT_NE(refusal(vpl(1, 0)).find("out of range"), std::string::npos);
    EXPECT_NE(refusal(radiosity(1e-37f, 0.01f)).find("patch size 1e-37 is out of range"), std::string::npos)
        << refusal(radiosity(1e-37f, 0.01f));
    EXPECT_NE(refusal(radiosity(2e6f, 0.01f)).find("1e-06 to 1e+06"), std::string::npos);
    EXPECT_NE(refusal(radiosity(std::numeric_limits<float>::quiet_NaN(), 0.01f)).find("patch size nan"),
              std::string::npos);
    EXPECT_NE(refusal(radiosity(0.25f, 1.0f)).find("tolerance 1 is out of range"), std::string::npos);
    BakeRequestMsg area;
    area.area_lights = kMaxAreaLights + 1;
    EXPECT_NE(refusal(area).find("area-light samples 4194305"), std::string::npos);
    BakeRequestMsg environment;
    environment.environment_lights = kMaxBakeEnvironmentLights + 1;
    EXPECT_NE(refusal(environment).find("environment lights 4194305"), std::string::npos);
}

TEST(BakeLimits, SettingsOfAnotherMethodAreNotChecked) {
    // A VPL bake's patch size is never used: no reason to refuse it.
    BakeRequestMsg request = vpl(1, 100);
    request.indirect.patch_size = 0.0f;
    EXPECT_TRUE(validate_bake_settings(request));
}

}  // namespace
}  // namespace lc
