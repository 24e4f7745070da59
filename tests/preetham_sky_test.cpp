// The Preetham sun and sky: the zenith matches the paper's zenith formula, the
// sky is brightest around the sun and black below the horizon, the sun
// reddens as it sets, and --sky is parsed and checked.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

#include "lightcuts/preetham_sky.h"

namespace lc {
namespace {

double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }

TEST(PreethamSky, ZenithLuminanceIsThePapersZenithFormula) {
    const SkyParameters sky{50.0f, 0.0f, 3.0f};
    const double theta_s = (90.0 - 50.0) * std::numbers::pi / 180.0;
    const double chi = (4.0 / 9.0 - 3.0 / 120.0) * (std::numbers::pi - 2.0 * theta_s);
    const double zenith_Y = (4.0453 * 3.0 - 4.9710) * std::tan(chi) - 0.2155 * 3.0 + 2.4192;
    EXPECT_NEAR(luminance(sky_radiance(sky, {0, 1, 0})), zenith_Y, 0.02 * zenith_Y);
}

TEST(PreethamSky, BrightestNearTheSunAndBlackBelowTheHorizon) {
    const SkyParameters sky{30.0f, 0.0f, 3.0f};
    const glm::dvec3 sun = sun_direction(sky);
    const glm::dvec3 near_sun = glm::normalize(sun + glm::dvec3(0, 0.1, 0));
    const glm::dvec3 away = glm::normalize(glm::dvec3(-sun.x, 0.5, -sun.z));
    EXPECT_GT(luminance(sky_radiance(sky, near_sun)), 2.0 * luminance(sky_radiance(sky, away)));
    EXPECT_EQ(sky_radiance(sky, {0, -0.2, 0.98}), glm::dvec3(0.0));
    for (const glm::dvec3 d : {near_sun, away, glm::dvec3(0, 1, 0), glm::normalize(glm::dvec3(1, 0.01, 0))}) {
        const glm::dvec3 L = sky_radiance(sky, d);
        EXPECT_TRUE(std::isfinite(L.x) && std::isfinite(L.y) && std::isfinite(L.z));
        EXPECT_GT(luminance(L), 0.0);
    }
    // A clear sky's blue: more blue than red away from the sun.
    const glm::dvec3 zenith = sky_radiance(sky, {0, 1, 0});
    EXPECT_GT(zenith.z, zenith.x);
}

TEST(PreethamSky, SunReddensAndDimsTowardsTheHorizon) {
    const glm::dvec3 high = sun_disc_radiance({80.0f, 0.0f, 3.0f});
    const glm::dvec3 low = sun_disc_radiance({3.0f, 0.0f, 3.0f});
    EXPECT_GT(luminance(high), luminance(low));
    EXPECT_GT(low.x / low.z, high.x / high.z);
    EXPECT_GT(luminance(high), 1000.0 * luminance(sky_radiance({80.0f, 0.0f, 3.0f}, {0, 1, 0})));
}

TEST(PreethamSky, SunDirectionFollowsElevationAndAzimuth) {
    const glm::dvec3 d = sun_direction({30.0f, 90.0f, 3.0f});
    EXPECT_NEAR(d.y, 0.5, 1e-6);
    EXPECT_NEAR(d.x, 0.0, 1e-6);
    EXPECT_NEAR(d.z, std::sqrt(3.0) / 2.0, 1e-6);
}

TEST(PreethamSky, ParsesAndChecksTheSkyFlag) {
    auto sky = parse_sky_parameters("45,120,2.5");
    ASSERT_TRUE(sky) << sky.error();
    EXPECT_EQ(*sky, (SkyParameters{45.0f, 120.0f, 2.5f}));
    EXPECT_NE(parse_sky_parameters("45,120").error().find("ELEVATION,AZIMUTH,TURBIDITY"), std::string::npos);
    EXPECT_NE(parse_sky_parameters("45,x,3").error().find("'x' is not a number"), std::string::npos);
    EXPECT_NE(parse_sky_parameters("95,0,3").error().find("elevation"), std::string::npos);
    EXPECT_NE(parse_sky_parameters("45,0,30").error().find("turbidity"), std::string::npos);
    EXPECT_FALSE(parse_sky_parameters("nan,0,3"));
}

TEST(PreethamSky, RasterHasTheSkyAboveAndBlackBelow) {
    const EquirectMap map = rasterize_sky({45.0f, 0.0f, 3.0f}, 64, 32);
    EXPECT_GT(luminance(glm::dvec3(map.at(10, 5))), 0.0);
    EXPECT_EQ(map.at(10, 20), glm::vec3(0.0f));
}

}  // namespace
}  // namespace lc
