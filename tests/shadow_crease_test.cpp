// Shadow rays in a contact crease (lightcuts/device/shadow_segment.glsl.h):
// a table leg standing on a floor, the furnished room's case. A point on the
// leg a rounding error below the floor, its normal horizontal, still sees a
// light above, and the leg still hides a light behind it.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <vector>

#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/occlusion/shadow_ray.h"

namespace lc {
namespace {

void add_quad(std::vector<glm::vec3>& v, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    v.insert(v.end(), {a, b, c, a, c, d});
}

// A 4 m floor at y = 0 and an 8 cm leg [0, 0.08] x [0, 0.72] x [0, 0.08] on it.
std::vector<glm::vec3> floor_and_leg() {
    std::vector<glm::vec3> v;
    add_quad(v, {-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 0, 2});
    const float s = 0.08f, h = 0.72f;
    add_quad(v, {0, 0, 0}, {s, 0, 0}, {s, h, 0}, {0, h, 0});  // z = 0
    add_quad(v, {0, 0, s}, {s, 0, s}, {s, h, s}, {0, h, s});  // z = s
    add_quad(v, {0, 0, 0}, {0, 0, s}, {0, h, s}, {0, h, 0});  // x = 0
    add_quad(v, {s, 0, 0}, {s, 0, s}, {s, h, s}, {s, h, 0});  // x = s
    add_quad(v, {0, h, 0}, {s, h, 0}, {s, h, s}, {0, h, s});  // top
    add_quad(v, {0, 0, 0}, {s, 0, 0}, {s, 0, s}, {0, 0, s});  // bottom, on the floor
    return v;
}

// The bias shadow_ray_bias gives a scene of this size (1e-4 of its extent).
constexpr double kBias = 1e-4 * 5.7;

double visible(const ShadowBvh& bvh, glm::dvec3 light, glm::dvec3 x, glm::dvec3 n) {
    return light_visibility(bvh, kBias, LightType::kPoint, light, glm::dvec3(0.0), x, n);
}

TEST(ShadowCrease, ALegsFootBelowTheFloorByARoundingErrorSeesALightAbove) {
    const ShadowBvh bvh = ShadowBvh::build(floor_and_leg());
    const glm::dvec3 light(0.04, 2.0, -1.5);  // above, in front of the leg's z = 0 face
    const glm::dvec3 front(0.0, 0.0, -1.0);
    // Where the face meets the floor, as a G-buffer gives it: at, above and
    // a float rounding error (and a hundred) below y = 0.
    for (double y : {0.0, 1e-7, -1e-7, -6e-8, -1e-5}) {
        for (double x : {0.001, 0.04, 0.079}) {
            EXPECT_EQ(visible(bvh, light, {x, y, 0.0}, front), 1.0) << "x " << x << " y " << y;
        }
    }
    // The floor in the crease, right against the face.
    for (double z : {-1e-7, -1e-5, -1e-3}) {
        EXPECT_EQ(visible(bvh, light, {0.04, 0.0, z}, {0, 1, 0}), 1.0) << "z " << z;
    }
    // A directional light from the same side.
    EXPECT_EQ(light_visibility(bvh, kBias, LightType::kDirectional, glm::dvec3(0.0),
                               glm::normalize(glm::dvec3(0.0, -1.0, 0.7)), {0.04, -1e-7, 0.0}, front),
              1.0);
}

TEST(ShadowCrease, TheLegStillCastsItsShadow) {
    const ShadowBvh bvh = ShadowBvh::build(floor_and_leg());
    // Behind the leg (z > 0.08) seen from a light in front of it, low.
    const glm::dvec3 light(0.04, 0.3, -1.0);
    for (double z : {0.0801, 0.085, 0.1}) {
        EXPECT_EQ(visible(bvh, light, {0.04, 0.0, z}, {0, 1, 0}), 0.0) << "z " << z;
    }
    // The floor in the crease behind the leg.
    EXPECT_EQ(visible(bvh, light, {0.04, -1e-7, 0.0800001}, {0, 1, 0}), 0.0);
}

}  // namespace
}  // namespace lc
