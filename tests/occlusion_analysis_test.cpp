// Which surfaces can hide a light (occlusion_analysis.h), and the effects
// decision built on it: an empty room needs no shadows, a furnished one tests
// only its furniture, and dropping the bounding triangles never changes a
// shadow ray's answer (checked against every shadow-casting triangle).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <random>
#include <vector>

#include "editor_client/render/analysis/occlusion_analysis.h"
#include "editor_client/render/analysis/scene_effects.h"
#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/occlusion/shadow_ray.h"
#include "editor_client/scene/scene_generator.h"

namespace lc::client {
namespace {

using ::testing::HasSubstr;

std::vector<glm::vec3> random_points(uint32_t count, glm::vec3 lo, glm::vec3 hi, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> out;
    for (uint32_t i = 0; i < count; ++i)
        out.push_back(lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng)));
    return out;
}

const std::vector<glm::vec3> kNoDirections;

TEST(OcclusionAnalysis, NoGeometryHidesNothing) {
    Scene scene;
    std::vector<glm::vec3> lights = {{0, 1, 0}};
    OcclusionAnalysis a = analyse_occlusion(scene, lights, kNoDirections);
    EXPECT_FALSE(a.possible);
    EXPECT_THAT(a.reason, HasSubstr("no surface casts shadows"));
    EXPECT_TRUE(a.occluders.empty());
}

TEST(OcclusionAnalysis, EmptyRoomWithLightsInsideNeedsNoShadows) {
    Scene room = make_room_scene();
    std::vector<glm::vec3> lights = random_points(200, kRoomLightBoxMin, kRoomLightBoxMax, 1);
    OcclusionAnalysis a = analyse_occlusion(room, lights, kNoDirections);
    EXPECT_FALSE(a.possible) << a.reason;
    EXPECT_EQ(a.casting_triangles, 12u);
    EXPECT_EQ(a.bounding_triangles, 12u);
    EXPECT_THAT(a.reason, HasSubstr("none can hide a light"));
}

TEST(OcclusionAnalysis, ALightOutsideTheRoomOrOnAWallCanBeHidden) {
    Scene room = make_room_scene();
    std::vector<glm::vec3> outside = {{0, 1, 0}, {0, 1, 6}};
    OcclusionAnalysis a = analyse_occlusion(room, outside, kNoDirections);
    EXPECT_TRUE(a.possible);
    // Only the front wall (z = 5) separates that light from the room.
    EXPECT_EQ(a.occluders.size(), 2u * 3u);
    std::vector<glm::vec3> on_wall = {{0, 1, 0}, {0, 1, kRoomMin.z}};
    EXPECT_TRUE(analyse_occlusion(room, on_wall, kNoDirections).possible);
}

TEST(OcclusionAnalysis, DirectionalLightsCrossTheCeilingButNotAnOpenFloor) {
    Scene room = make_room_scene();
    std::vector<glm::vec3> down = {{0.0f, -1.0f, 0.0f}};
    OcclusionAnalysis closed = analyse_occlusion(room, {}, down);
    EXPECT_TRUE(closed.possible);
    // Straight down: the ceiling (y = 3) is the only surface the sunlight crosses.
    EXPECT_EQ(closed.occluders.size(), 2u * 3u);
    for (const glm::vec3& v : closed.occluders) EXPECT_FLOAT_EQ(v.y, kRoomMax.y);
    // Slanted towards -x: the rays towards the sun also head for the -x wall.
    std::vector<glm::vec3> slanted = {{0.3f, -1.0f, 0.0f}};
    EXPECT_EQ(analyse_occlusion(room, {}, slanted).occluders.size(), 4u * 3u);

    Scene floor;
    floor.meshes.push_back(room.meshes[0]);  // the floor quad alone
    floor.materials = room.materials;
    EXPECT_FALSE(analyse_occlusion(floor, {}, slanted).possible);
}

TEST(OcclusionAnalysis, FurnitureIsTestedAndTheRoomIsNot) {
    Scene room = make_furnished_room_scene();
    std::vector<glm::vec3> lights = random_points(300, kRoomLightBoxMin, kRoomLightBoxMax, 2);
    OcclusionAnalysis a = analyse_occlusion(room, lights, kNoDirections);
    EXPECT_TRUE(a.possible);
    EXPECT_GT(a.occluders.size(), 0u);
    EXPECT_GE(a.bounding_triangles, 12u);  // at least the six walls
    EXPECT_EQ(a.occluders.size() / 3 + a.bounding_triangles, a.casting_triangles);
    EXPECT_THAT(a.reason, HasSubstr("may hide a light"));
    // No kept triangle lies on a wall, floor or ceiling plane.
    for (size_t t = 0; t < a.occluders.size(); t += 3) {
        bool on_room_plane = true;
        for (int axis = 0; axis < 3 && on_room_plane; ++axis) {
            for (float plane : {kRoomMin[axis], kRoomMax[axis]}) {
                if (a.occluders[t][axis] == plane && a.occluders[t + 1][axis] == plane &&
                    a.occluders[t + 2][axis] == plane)
                    on_room_plane = false;
            }
        }
        EXPECT_TRUE(on_room_plane) << "a room surface was kept as an occluder";
    }
    // --shadows on keeps them all.
    EXPECT_EQ(analyse_occlusion(room, lights, kNoDirections, false).occluders.size(),
              3 * a.casting_triangles);
}

TEST(OcclusionAnalysis, SurfacesThatLetLightThroughAreNotOccluders) {
    Scene room = make_furnished_room_scene();
    for (Material& m : room.materials) m.casts_shadows = false;
    std::vector<glm::vec3> lights = {{0, 1, 0}};
    OcclusionAnalysis a = analyse_occlusion(room, lights, kNoDirections);
    EXPECT_FALSE(a.possible);
    EXPECT_EQ(a.casting_triangles, 0u);
}

// Dropping the bounding triangles is exact: shadow rays from random points on
// every surface (offset along the normal facing the light, as the renderer
// does) to every light agree with rays tested against every triangle.
TEST(OcclusionAnalysis, DroppingBoundingTrianglesNeverChangesVisibility) {
    Scene room = make_furnished_room_scene();
    std::vector<glm::vec3> lights = random_points(40, kRoomLightBoxMin, kRoomLightBoxMax, 3);
    OcclusionAnalysis kept = analyse_occlusion(room, lights, kNoDirections);
    OcclusionAnalysis all = analyse_occlusion(room, lights, kNoDirections, false);
    ShadowBvh kept_bvh = ShadowBvh::build(kept.occluders);
    ShadowBvh all_bvh = ShadowBvh::build(all.occluders);
    const double bias = shadow_ray_bias(room);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    size_t rays = 0, hidden = 0;
    for (size_t t = 0; t < all.occluders.size(); t += 3) {
        const glm::dvec3 a(all.occluders[t]), b(all.occluders[t + 1]), c(all.occluders[t + 2]);
        const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        for (int sample = 0; sample < 8; ++sample) {
            double s = u(rng), r = u(rng);
            if (s + r > 1.0) s = 1.0 - s, r = 1.0 - r;
            const glm::dvec3 x = a + s * (b - a) + r * (c - a);
            for (const glm::vec3& light : lights) {
                const glm::dvec3 l(light);
                // The side of the surface that faces the light is the lit one.
                const glm::dvec3 facing = glm::dot(l - x, n) >= 0.0 ? n : -n;
                if (glm::dot(l - x, facing) <= 0.0) continue;
                const double v_all = light_visibility(all_bvh, bias, LightType::kPoint, l, {},
                                                      x, facing);
                const double v_kept = light_visibility(kept_bvh, bias, LightType::kPoint, l, {},
                                                       x, facing);
                ASSERT_EQ(v_all, v_kept) << "triangle " << t / 3 << " sample " << sample;
                ++rays;
                hidden += v_all == 0.0;
            }
        }
    }
    std::printf("  %zu rays, %zu hidden\n", rays, hidden);
    EXPECT_GT(rays, 10000u);
    EXPECT_GT(hidden, rays / 20) << "the furniture should hide some lights";
}

TEST(SceneEffects, ShadowDecisionFollowsTheSceneAndTheUser) {
    Scene empty = make_room_scene();
    empty.lights.push_back({});
    empty.lights.back().position = {0.0f, 1.5f, 0.0f};
    empty.lights.back().intensity = 1.0f;
    SceneEffects e = analyse_scene_effects(empty, nullptr);
    EXPECT_FALSE(e.shadows);
    ASSERT_FALSE(e.skipped().empty());
    bool reported = false;
    for (const EffectDecision& d : e.skipped())
        if (d.name.find("shadows") != std::string::npos) {
            reported = true;
            EXPECT_THAT(d.reason, HasSubstr("bound the scene"));
        }
    EXPECT_TRUE(reported);

    Scene furnished = make_furnished_room_scene();
    furnished.lights = empty.lights;
    furnished.lights.back().position = {0.0f, 0.3f, 0.0f};  // under the table
    SceneEffects f = analyse_scene_effects(furnished, nullptr);
    EXPECT_TRUE(f.shadows);
    EXPECT_FALSE(f.occluders.empty());
    EXPECT_FALSE(analyse_scene_effects(furnished, nullptr, ShadowMode::kOff).shadows);
    SceneEffects forced = analyse_scene_effects(furnished, nullptr, ShadowMode::kOn);
    EXPECT_TRUE(forced.shadows);
    EXPECT_GT(forced.occluders.size(), f.occluders.size());
}

TEST(ShadowMode, ParsesTheThreeNamesAndRejectsOthers) {
    EXPECT_EQ(*parse_shadow_mode("auto"), ShadowMode::kAuto);
    EXPECT_EQ(*parse_shadow_mode("on"), ShadowMode::kOn);
    EXPECT_EQ(*parse_shadow_mode("off"), ShadowMode::kOff);
    Result<ShadowMode> bad = parse_shadow_mode("maybe");
    ASSERT_FALSE(bad.ok());
    EXPECT_THAT(bad.error(), HasSubstr("maybe"));
}

}  // namespace
}  // namespace lc::client
