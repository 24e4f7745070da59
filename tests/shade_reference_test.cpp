// The exact reference: the sum of every light's contribution.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "tree_fixtures.h"

namespace lc::test {
namespace {

TEST(ShadeReference, IsTheSumOfLights) {
    std::mt19937_64 rng(7);
    std::vector<SceneLight> lights =
        random_lights_in_box(rng, 40, LightType::kPoint, {-5, -5, 1}, {5, 5, 4}, true);
    auto spots = random_lights_in_box(rng, 20, LightType::kSpot, {-5, -5, 1}, {5, 5, 4}, true);
    auto suns = random_lights_in_box(rng, 5, LightType::kDirectional, {0, 0, 0}, {0, 0, 0}, false);
    lights.insert(lights.end(), spots.begin(), spots.end());
    lights.insert(lights.end(), suns.begin(), suns.end());
    const SurfacePoint p = surface({0.5, -0.25, 0}, {0.1, 0.2, 1});
    glm::dvec3 sum(0.0);
    for (const SceneLight& l : lights) sum += shade_light(l, p);
    const glm::dvec3 ref = shade_reference(lights, p);
    expect_near_rel(ref, sum, 1e-14);
    EXPECT_GT(ref.x, 0.0);
    EXPECT_EQ(shade_reference({}, p), glm::dvec3(0.0));
}

}  // namespace
}  // namespace lc::test
