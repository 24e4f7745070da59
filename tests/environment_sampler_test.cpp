// The environment as directional lights: energy conserved stratum by stratum,
// a uniform environment's irradiance on a floor and a wall, strata following
// luminance, the sun's disc, the light budget, determinism.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

#include "lightcuts/seeded_mixer.h"
#include "lightmass_server/emitters/environment_sampler.h"

namespace lc::bake {
namespace {

constexpr double kPi = std::numbers::pi;

EquirectMap uniform_map(uint32_t width, uint32_t height, glm::vec3 radiance) {
    return EquirectMap{width, height, std::vector<glm::vec3>(size_t(width) * height, radiance)};
}

glm::dvec3 lux_of(const SceneLight& light) { return glm::dvec3(light.color) * double(light.intensity); }
glm::dvec3 towards(const SceneLight& light) { return -glm::dvec3(light.direction); }

// Irradiance (green channel) on a surface of normal n from the lights that
// reach it; `ground` blocks every light from below the horizon.
double irradiance(const std::vector<SceneLight>& lights, const glm::dvec3& n, bool ground) {
    double sum = 0.0;
    for (const SceneLight& light : lights) {
        if (ground && towards(light).y <= 0.0) continue;
        sum += lux_of(light).y * std::max(0.0, glm::dot(n, towards(light)));
    }
    return sum;
}

glm::dvec3 total_lux(const std::vector<SceneLight>& lights) {
    glm::dvec3 sum(0.0);
    for (const SceneLight& light : lights) sum += lux_of(light);
    return sum;
}

TEST(EnvironmentSampler, UniformEnvironmentGivesPiLOnAnUpwardFloor) {
    const EquirectMap map = uniform_map(256, 128, glm::vec3(1.0f));
    const auto lights = sample_equirect_map(map, 0.0, 1.0, 3000, 7);
    ASSERT_EQ(lights.size(), 3000u);
    EXPECT_NEAR(irradiance(lights, {0, 1, 0}, false), kPi, 0.005 * kPi);
}

TEST(EnvironmentSampler, WallAboveAGroundGetsHalfTheFloorsIrradiance) {
    const EquirectMap map = uniform_map(256, 128, glm::vec3(1.0f));
    const auto lights = sample_equirect_map(map, 0.0, 1.0, 3000, 7);
    const double floor = irradiance(lights, {0, 1, 0}, true);
    for (const glm::dvec3 n : {glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(-0.6, 0, 0.8)})
        EXPECT_NEAR(irradiance(lights, n, true) / floor, 0.5, 0.01) << n.x << " " << n.z;
}

TEST(EnvironmentSampler, StrataConserveTheEnvironmentsEnergyPerChannel) {
    EquirectMap map = uniform_map(97, 41, glm::vec3(0.0f));
    SplitMix64 random(11);
    glm::dvec3 expected(0.0);
    for (uint32_t y = 0; y < map.height; ++y) {
        for (uint32_t x = 0; x < map.width; ++x) {
            // A quarter of the texels dark, a few very bright, the rest coloured.
            const double pick = random.uniform();
            glm::vec3 radiance = pick < 0.25 ? glm::vec3(0.0f)
                                 : pick < 0.27 ? glm::vec3(500.0f, 400.0f, 300.0f)
                                               : glm::vec3(float(random.uniform()), float(random.uniform()),
                                                           float(random.uniform()));
            map.texels[size_t(y) * map.width + x] = radiance;
            expected += glm::dvec3(radiance) * equirect_texel_solid_angle(y, map.width, map.height);
        }
    }
    for (uint32_t count : {1u, 10u, 1000u, 20000u}) {
        const auto lights = sample_equirect_map(map, 0.3, 2.0, count, 5);
        EXPECT_EQ(lights.size(), count);
        const glm::dvec3 got = total_lux(lights);
        for (int c = 0; c < 3; ++c) // Exact in double; each light keeps its irradiance as float colour times float intensity.
            EXPECT_NEAR(got[c], 2.0 * expected[c], 1e-6 * expected[c]) << count;
    }
}

TEST(EnvironmentSampler, StrataFollowLuminance) {
    // The upper half ten times brighter: about 10 of every 11 lights come from it.
    EquirectMap map = uniform_map(128, 64, glm::vec3(1.0f));
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 128; ++x) map.texels[size_t(y) * 128 + x] = glm::vec3(10.0f);
    const auto lights = sample_equirect_map(map, 0.0, 1.0, 2200, 3);
    size_t upper = 0;
    for (const SceneLight& light : lights) upper += towards(light).y > 0.0;
    EXPECT_NEAR(double(upper) / lights.size(), 10.0 / 11.0, 0.01);
    // Equal-power strata: every light carries the same irradiance.
    const double mean = total_lux(lights).y / lights.size();
    for (const SceneLight& light : lights) EXPECT_NEAR(lux_of(light).y / mean, 1.0, 1e-5);
}

TEST(EnvironmentSampler, RotationTurnsTheLightsAboutTheVertical) {
    EquirectMap map = uniform_map(64, 32, glm::vec3(0.0f));
    map.texels[size_t(10) * 64 + 5] = glm::vec3(100.0f);
    const auto plain = sample_equirect_map(map, 0.0, 1.0, 1, 1);
    const auto turned = sample_equirect_map(map, kPi / 2.0, 1.0, 1, 1);
    ASSERT_EQ(plain.size(), 1u);
    ASSERT_EQ(turned.size(), 1u);
    const glm::dvec3 a = towards(plain[0]), b = towards(turned[0]);
    EXPECT_NEAR(a.y, b.y, 1e-6);
    // phi grows by pi/2: (x, z) turns to (-z, x).
    EXPECT_NEAR(b.x, -a.z, 1e-6);
    EXPECT_NEAR(b.z, a.x, 1e-6);
}

TEST(EnvironmentSampler, SunDiscLightsSumToTheDiscsIrradianceInsideTheDisc) {
    const SkyParameters sky{30.0f, 45.0f, 3.0f};
    const auto lights = sample_sun_disc(sky, 1.0, 64, 9);
    ASSERT_EQ(lights.size(), 64u);
    const double solid_angle = 2.0 * kPi * (1.0 - std::cos(sun_angular_radius()));
    const glm::dvec3 expected = sun_disc_radiance(sky) * solid_angle;
    const glm::dvec3 got = total_lux(lights);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-6 * expected[c]);
    // A clear sun at 30 degrees gives tens of klux (kcd/m^2 x sr).
    EXPECT_GT(expected.y, 20.0);
    EXPECT_LT(expected.y, 150.0);
    const glm::dvec3 sun = sun_direction(sky);
    for (const SceneLight& light : lights)
        EXPECT_LE(std::acos(std::min(1.0, glm::dot(towards(light), sun))), sun_angular_radius() * 1.0001);
}

TEST(EnvironmentSampler, SunAndSkyShareTheBudgetInThePapersRatio) {
    Environment environment;
    environment.sky = SkyParameters{40.0f, 10.0f, 2.5f};
    auto sampled = sample_environment(environment, 0, 1);
    ASSERT_TRUE(sampled) << sampled.error();
    EXPECT_EQ(sampled->lights.size(), kDefaultEnvironmentLights);
    EXPECT_NE(sampled->census.find("38 sun + 2962 sky lights"), std::string::npos) << sampled->census;
    // The sky lies above the horizon: no light from below.
    for (const SceneLight& light : sampled->lights) EXPECT_GT(towards(light).y, 0.0);
}

TEST(EnvironmentSampler, MapCensusNamesTheMapAndTheLights) {
    Environment environment;
    environment.map = uniform_map(32, 16, glm::vec3(1.0f));
    auto sampled = sample_environment(environment, 500, 1);
    ASSERT_TRUE(sampled) << sampled.error();
    EXPECT_EQ(sampled->census, "environment: simulated (32 x 16 map, 500 lights)");
    environment.map = uniform_map(32, 16, glm::vec3(0.0f));
    sampled = sample_environment(environment, 500, 1);
    ASSERT_TRUE(sampled) << sampled.error();
    EXPECT_TRUE(sampled->lights.empty());
    EXPECT_EQ(sampled->census, "environment: skipped (it emits no light)");
}

TEST(EnvironmentSampler, RefusesZeroOrAbsurdBudgets) {
    Environment map;
    map.map = uniform_map(8, 4, glm::vec3(1.0f));
    Environment sky;
    sky.sky = SkyParameters{};
    EXPECT_FALSE(validate_environment_light_count(map, 0));
    EXPECT_TRUE(validate_environment_light_count(map, 1));
    EXPECT_TRUE(validate_environment_light_count(map, kMaxEnvironmentLights));
    EXPECT_FALSE(validate_environment_light_count(map, kMaxEnvironmentLights + 1));
    EXPECT_FALSE(validate_environment_light_count(sky, 1));
    EXPECT_TRUE(validate_environment_light_count(sky, 2));
    auto refused = sample_environment(map, kMaxEnvironmentLights + 1, 0);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().find(std::to_string(kMaxEnvironmentLights)), std::string::npos) << refused.error();
}

TEST(EnvironmentSampler, DeterministicForASeed) {
    EquirectMap map = uniform_map(64, 32, glm::vec3(1.0f));
    map.texels[100] = glm::vec3(50.0f, 20.0f, 5.0f);
    const auto a = sample_equirect_map(map, 0.0, 1.0, 700, 42);
    const auto b = sample_equirect_map(map, 0.0, 1.0, 700, 42);
    const auto c = sample_equirect_map(map, 0.0, 1.0, 700, 43);
    ASSERT_EQ(a.size(), b.size());
    bool differs = false;
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].direction, b[i].direction);
        EXPECT_EQ(a[i].intensity, b[i].intensity);
        EXPECT_EQ(a[i].guid, b[i].guid);
        differs = differs || a[i].direction != c[i].direction;
    }
    EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace lc::bake
