// Clicking in the view: camera rays, surface hits on the room, light picking.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <random>

#include "editor_client/editor/picking.h"
#include "editor_client/scene/scene_generator.h"

namespace lc::client {
namespace {

RenderCamera looking(glm::vec3 eye, glm::vec3 target, float yfov = 0.9f) {
    RenderCamera camera;
    camera.eye = eye;
    camera.target = target;
    camera.yfov = yfov;
    return camera;
}

TEST(EditorPicking, CentreRayLooksAtTheTargetAndCornersSpanTheFieldOfView) {
    const RenderCamera camera = looking({0, 1.5f, 4}, {0, 1.5f, 0}, 0.9f);
    // Even size: the centre lies between pixels 319 and 320.
    Ray centre = camera_ray(camera, 319.5, 179.5, 640, 360);
    EXPECT_NEAR(centre.direction.x, 0.0, 1e-12);
    EXPECT_NEAR(centre.direction.y, 0.0, 1e-12);
    EXPECT_NEAR(centre.direction.z, -1.0, 1e-12);
    // The top row's centre: half the vertical field of view up (less half a pixel).
    Ray top = camera_ray(camera, 319.5, -0.5, 640, 360);
    EXPECT_NEAR(std::atan2(top.direction.y, -top.direction.z), 0.45, 1e-6);
    Ray right = camera_ray(camera, 639.5, 179.5, 640, 360);
    EXPECT_NEAR(right.direction.x / -right.direction.z, std::tan(0.45) * 640.0 / 360.0, 1e-6);
    EXPECT_NEAR(glm::length(right.direction), 1.0, 1e-12);
}

TEST(EditorPicking, RayHitsTheRoomsFloorWallAndCeiling) {
    const Scene room = make_room_scene();
    // Straight down from inside the room: the floor at y = 0.
    auto floor = pick_surface(room, Ray{{1.0, 2.0, -1.5}, {0.0, -1.0, 0.0}});
    ASSERT_TRUE(floor);
    EXPECT_NEAR(floor->position.x, 1.0f, 1e-5f);
    EXPECT_NEAR(floor->position.y, 0.0f, 1e-5f);
    EXPECT_NEAR(floor->position.z, -1.5f, 1e-5f);
    EXPECT_NEAR(floor->distance, 2.0, 1e-9);
    EXPECT_NEAR(floor->normal.y, 1.0f, 1e-6f);
    const glm::vec3 above = light_position_above(*floor, 0.25f);
    EXPECT_NEAR(above.y, 0.25f, 1e-6f);

    auto ceiling = pick_surface(room, Ray{{0.0, 1.0, 0.0}, {0.0, 1.0, 0.0}});
    ASSERT_TRUE(ceiling);
    EXPECT_NEAR(ceiling->position.y, kRoomMax.y, 1e-5f);
    EXPECT_NEAR(ceiling->normal.y, -1.0f, 1e-6f);  // facing the ray's origin

    auto wall = pick_surface(room, Ray{{0.0, 1.0, 0.0}, {0.0, 0.0, -1.0}});
    ASSERT_TRUE(wall);
    EXPECT_NEAR(wall->position.z, kRoomMin.z, 1e-5f);

    // From outside, looking away: nothing.
    EXPECT_FALSE(pick_surface(room, Ray{{0.0, 1.0, 20.0}, {0.0, 0.0, 1.0}}));
}

TEST(EditorPicking, RandomRaysFromInsideAlwaysHitTheBoxBoundary) {
    const Scene room = make_room_scene();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 200; ++i) {
        glm::dvec3 d(u(rng), u(rng), u(rng));
        if (glm::length(d) < 1e-3) continue;
        d = glm::normalize(d);
        const glm::dvec3 origin(0.3 * u(rng), 1.5 + u(rng), 0.3 * u(rng));
        auto hit = pick_surface(room, Ray{origin, d});
        ASSERT_TRUE(hit) << i;
        // Slab distance to the room's box: the exact answer.
        double t_exit = 1e300;
        for (int a = 0; a < 3; ++a) {
            if (d[a] > 0) t_exit = std::min(t_exit, (kRoomMax[a] - origin[a]) / d[a]);
            if (d[a] < 0) t_exit = std::min(t_exit, (kRoomMin[a] - origin[a]) / d[a]);
        }
        EXPECT_NEAR(hit->distance, t_exit, 1e-6) << i;
    }
}

TEST(EditorPicking, PicksTheLightNearestTheRay) {
    Scene scene = make_room_scene();
    SceneLight a, b, sun;
    a.position = {0, 1, -2};
    b.position = {0.5f, 1, -2};
    sun.type = LightType::kDirectional;
    sun.direction = {0, 0, -1};
    scene.lights = {sun, a, b};
    const Ray ray{{0.0, 1.0, 0.0}, {0.0, 0.0, -1.0}};
    EXPECT_EQ(pick_light(scene, ray, 0.05), std::optional<size_t>(1));
    const Ray toward_b{{0.0, 1.0, 0.0}, glm::normalize(glm::dvec3(0.45, 0.0, -2.0))};
    EXPECT_EQ(pick_light(scene, toward_b, 0.05), std::optional<size_t>(2));
    // Behind the origin or too far off the ray: none.
    EXPECT_FALSE(pick_light(scene, Ray{{0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}, 0.05));
    EXPECT_FALSE(pick_light(scene, Ray{{0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}}, 0.05));
}

}  // namespace
}  // namespace lc::client
