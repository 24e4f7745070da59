// One light's exact radiance (shading_model.h) against hand-computed
// values: inverse square with the range window, the spot ramp, directional
// lux, and the degenerate points (on a light, grazing normals).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/shading_model.h"
#include "tree_fixtures.h"

namespace lc::test {
namespace {

TEST(ShadeLight, PointLightMatchesHandComputedValue) {
    // 4 cd at distance 2 straight above: E = 4 / 4 = 1 lux, L = albedo / pi.
    SceneLight light = make_light(LightType::kPoint, {0, 0, 2}, 4.0f);
    glm::dvec3 L = shade_light(light, surface({0, 0, 0}, {0, 0, 1}, {0.5, 1.0, 0.25}));
    expect_near_rel(L, glm::dvec3(0.5, 1.0, 0.25) / kPi, 1e-12);
    // Range 4 at distance 2: window = (1 - (1/2)^4)^2.
    light.range = 4.0f;
    L = shade_light(light, surface({0, 0, 0}));
    expect_near_rel(L, glm::dvec3(0.87890625 / kPi), 1e-12);
    // Beyond the range: nothing.
    EXPECT_EQ(shade_light(light, surface({0, 0, -2.5})).x, 0.0);
    // 45 degrees off the normal, distance sqrt(8): cos = 1/sqrt2.
    light.range = 0.0f;
    L = shade_light(light, surface({2, 0, 0}));
    expect_near_rel(L, glm::dvec3(4.0 / 8.0 / std::sqrt(2.0) / kPi), 1e-12);
}

TEST(ShadeLight, SpotAttenuationFollowsTheModel) {
    SceneLight spot = make_light(LightType::kSpot, {0, 0, 1}, 1.0f);
    spot.direction = {0, 0, -1};
    spot.inner_cone_angle = 0.2f;
    spot.outer_cone_angle = 0.6f;
    // On the axis: full intensity.
    expect_near_rel(shade_light(spot, surface({0, 0, 0})), glm::dvec3(1.0 / kPi), 1e-12);
    // At 0.4 rad off the axis.
    const double angle = 0.4;
    const glm::dvec3 x(std::tan(angle), 0.0, 0.0);
    const double d2 = 1.0 + x.x * x.x;
    const double cos_theta = 1.0 / std::sqrt(d2);
    const double ci = std::cos(double(0.2f)), co = std::cos(double(0.6f));
    const double a = std::clamp((std::cos(angle) - co) / (ci - co), 0.0, 1.0);
    expect_near_rel(shade_light(spot, surface(x)), glm::dvec3(a * a * cos_theta / d2 / kPi), 1e-9);
    // Outside the outer cone: nothing; exactly on its edge: nothing either.
    EXPECT_EQ(shade_light(spot, surface({std::tan(0.7), 0, 0})).x, 0.0);
    const glm::dvec3 edge(std::tan(double(0.6f)), 0, 0);
    EXPECT_NEAR(shade_light(spot, surface(edge)).x, 0.0, 1e-12);
}

TEST(ShadeLight, DirectionalUsesLuxAndCosine) {
    SceneLight sun = make_light(LightType::kDirectional, {0, 0, 0}, 3.0f, {1.0f, 0.5f, 0.0f});
    sun.direction = glm::normalize(glm::vec3(0, -1, -1));
    // cos(45 deg) between the normal and the direction the light comes from.
    const glm::dvec3 L = shade_light(sun, surface({5, 5, 5}));
    const double c = glm::dot(glm::dvec3(0, 0, 1), -glm::dvec3(sun.direction));
    expect_near_rel(L, glm::dvec3(3.0, 1.5, 0.0) * c / kPi, 1e-12);
    // Lit from behind: nothing.
    sun.direction = {0, 0, 1};
    EXPECT_EQ(shade_light(sun, surface({0, 0, 0})).x, 0.0);
}

TEST(ShadeLight, OrientedLightIsACosineEmitter) {
    // 2 cd along the normal (down) from 1 m above: E = 2 lux straight below.
    SceneLight panel = make_light(LightType::kOriented, {0, 0, 1}, 2.0f, {1.0f, 0.5f, 0.25f});
    panel.direction = {0, 0, -1};
    expect_near_rel(shade_light(panel, surface({0, 0, 0})), glm::dvec3(2.0, 1.0, 0.5) / kPi, 1e-12);
    // At 60 degrees off the normal the emitter's cosine (1/2) joins the
    // receiver's (1/2) and the inverse square (distance 2).
    const glm::dvec3 x(std::tan(kPi / 3.0), 0.0, 0.0);
    expect_near_rel(shade_light(panel, surface(x)),
                    glm::dvec3(2.0, 1.0, 0.5) * 0.5 * 0.5 / 4.0 / kPi, 1e-9);
    // Behind the emitting side and in its plane: nothing.
    EXPECT_EQ(shade_light(panel, surface({0, 0, 2}, {0, 0, -1})).x, 0.0);
    EXPECT_NEAR(shade_light(panel, surface({3, 0, 1}, {-1, 0, 0})).x, 0.0, 1e-15);
}

TEST(ShadeLight, PointExactlyOnALightStaysFinite) {
    SceneLight light = make_light(LightType::kPoint, {1, 2, 3}, 1e6f);
    const glm::dvec3 L = shade_light(light, surface({1, 2, 3}));
    EXPECT_TRUE(finite3(L));
    EXPECT_EQ(L.x, 0.0);  // the direction to the light is undefined: no contribution
    // A hair away along the normal the clamp of the inverse square applies.
    const glm::dvec3 near = shade_light(light, surface({1, 2, 3 - 1e-9}));
    EXPECT_TRUE(finite3(near));
    expect_near_rel(near, glm::dvec3(1e6 / (shading::kMinDistance * shading::kMinDistance) / kPi),
                    1e-9);
}

TEST(ShadeLight, GrazingNormalsGiveZeroNotNaN) {
    SceneLight light = make_light(LightType::kPoint, {1, 0, 0}, 1.0f);
    EXPECT_EQ(shade_light(light, surface({0, 0, 0}, {0, 0, 1})).x, 0.0);
    const glm::dvec3 tiny = shade_light(light, surface({0, 0, 0}, {1e-12, 0, 1}));
    EXPECT_TRUE(finite3(tiny));
    EXPECT_GT(tiny.x, 0.0);
    EXPECT_LT(tiny.x, 1e-11);
    EXPECT_EQ(shade_light(light, surface({0, 0, 0}, {-1e-12, 0, 1})).x, 0.0);
}

}  // namespace
}  // namespace lc::test
