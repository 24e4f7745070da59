// The environment as the background where no geometry is hit
// (shaders/background.glsl), on lavapipe: a uniform map shows its radiance
// exactly in every lighting mode, through the tone curve; a sky matches the
// CPU Preetham model; the map's rotation turns the background and the
// server's sampled light alike; no environment leaves the background black.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "editor_client/render/renderer.h"
#include "lightcuts/preetham_sky.h"
#include "lightcuts/tone_mapping.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

constexpr uint32_t kSize = 33;  // odd: the centre pixel's eye ray is the camera's axis

// A wide ground and, with `box`, a unit cube standing on it at the origin.
Scene ground_scene(bool box) {
    Scene scene;
    scene.materials = {test::white_lambert()};
    scene.meshes.push_back(test::make_quad({-50, 0, 50}, {100, 0, 0}, {0, 0, -100}, 0));
    if (box) {
        scene.meshes.push_back(test::make_quad({-0.5f, 0, 0.5f}, {1, 0, 0}, {0, 1, 0}, 0));     // +Z
        scene.meshes.push_back(test::make_quad({0.5f, 0, -0.5f}, {-1, 0, 0}, {0, 1, 0}, 0));    // -Z
        scene.meshes.push_back(test::make_quad({0.5f, 0, 0.5f}, {0, 0, -1}, {0, 1, 0}, 0));     // +X
        scene.meshes.push_back(test::make_quad({-0.5f, 0, -0.5f}, {0, 0, 1}, {0, 1, 0}, 0));    // -X
        scene.meshes.push_back(test::make_quad({-0.5f, 1, 0.5f}, {1, 0, 0}, {0, 0, -1}, 0));    // top
    }
    scene.bounds_min = {-50, 0, -50};
    scene.bounds_max = {50, 1, 50};
    return scene;
}

std::shared_ptr<Environment> uniform_environment(glm::vec3 radiance) {
    auto environment = std::make_shared<Environment>();
    environment->map = EquirectMap{32, 16, std::vector<glm::vec3>(32 * 16, radiance)};
    return environment;
}

LightTree environment_tree(const Environment& environment, uint32_t count) {
    auto sampled = bake::sample_environment(environment, count, 7);
    EXPECT_TRUE(sampled) << sampled.error();
    return test::agglomerative_tree(sampled ? sampled->lights : std::vector<SceneLight>{});
}

RenderSettings looking(glm::vec3 eye, glm::vec3 target, RenderMode mode = RenderMode::kReference) {
    RenderSettings settings;
    settings.mode = mode;
    settings.criterion = CutCriterion::kBound;
    settings.width = settings.height = kSize;
    settings.camera.eye = eye;
    settings.camera.target = target;
    settings.camera.yfov = 0.8f;
    return settings;
}

// The eye ray through pixel (x, y) of a square frame, from the camera alone
// (a pinhole: +Y up, rows downwards), independent of the renderer's matrices.
glm::dvec3 pinhole_ray(const RenderCamera& camera, uint32_t x, uint32_t y) {
    const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target - camera.eye));
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(camera.up)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double t = std::tan(0.5 * double(camera.yfov));
    const double sx = 2.0 * (x + 0.5) / kSize - 1.0;
    const double sy = 2.0 * (y + 0.5) / kSize - 1.0;
    return glm::normalize(forward + sx * t * right - sy * t * up);
}

glm::vec3 hdr_at(const std::vector<float>& hdr, uint32_t x, uint32_t y) {
    const size_t i = (size_t(y) * kSize + x) * 4;
    return {hdr[i], hdr[i + 1], hdr[i + 2]};
}

class BackgroundRender : public test::VulkanTest {};

TEST_F(BackgroundRender, UniformEnvironmentShowsItsRadianceExactlyInEveryMode) {
    const glm::vec3 L(0.25f, 0.5f, 1.5f);
    const std::shared_ptr<Environment> environment = uniform_environment(L);
    const LightTree tree = environment_tree(*environment, 256);
    const Scene scene = ground_scene(false);
    auto renderer = test::create_renderer(*context_, scene, &tree);
    ASSERT_TRUE(renderer) << renderer.error();
    ASSERT_TRUE((*renderer)->set_environment(environment));
    struct Case {
        RenderMode mode;
        CutCriterion criterion;
        BoundSearch search;
    };
    for (const Case& c : {Case{RenderMode::kReference, CutCriterion::kBound, BoundSearch::kWalk},
                          Case{RenderMode::kLightcuts, CutCriterion::kBound, BoundSearch::kWalk},
                          Case{RenderMode::kLightcuts, CutCriterion::kBound, BoundSearch::kHeap},
                          Case{RenderMode::kLightcuts, CutCriterion::kRadius, BoundSearch::kWalk}}) {
        SCOPED_TRACE(std::string(render_mode_name(c.mode)) + " " + criterion_name(c.criterion) + " " +
                     bound_search_name(c.search));
        RenderSettings settings = looking({0, 1, 0}, {0, 1, -5}, c.mode);
        settings.criterion = c.criterion;
        settings.bound_search = c.search;
        settings.exposure = 0.5f;
        ASSERT_TRUE((*renderer)->render(settings));
        auto hdr = (*renderer)->read_hdr();
        auto display = (*renderer)->read_display();
        ASSERT_TRUE(hdr && display);
        size_t background = 0;
        for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
            if ((*hdr)[4 * i + 3] != 0.0f) continue;  // geometry
            ++background;
            for (int ch = 0; ch < 3; ++ch) {
                ASSERT_EQ((*hdr)[4 * i + ch], L[ch]) << "pixel " << i;
                // Tone-mapped like any radiance: exposure, filmic curve, sRGB.
                ASSERT_EQ((*display)[4 * i + ch], tone::to_display_byte(L[ch], settings.exposure))
                    << "pixel " << i;
            }
        }
        // The upper half of the frame looks over the horizon.
        EXPECT_GE(background, size_t(kSize) * (kSize / 2));
    }
}

TEST_F(BackgroundRender, IntensityScalesTheBackgroundAndNoEnvironmentLeavesItBlack) {
    const glm::vec3 L(0.25f, 0.5f, 1.5f);
    auto environment = uniform_environment(L);
    environment->intensity = 3.0f;
    const Scene scene = ground_scene(false);
    auto renderer = test::create_renderer(*context_, scene, nullptr);
    ASSERT_TRUE(renderer) << renderer.error();
    const RenderSettings settings = looking({0, 1, 0}, {0, 1, -5});
    for (bool with_environment : {true, false}) {
        ASSERT_TRUE((*renderer)->set_environment(with_environment ? environment : nullptr));
        ASSERT_TRUE((*renderer)->render(settings));
        auto hdr = (*renderer)->read_hdr();
        auto display = (*renderer)->read_display();
        ASSERT_TRUE(hdr && display);
        const glm::vec3 expected = with_environment ? 3.0f * L : glm::vec3(0.0f);
        for (uint32_t x = 0; x < kSize; ++x) {
            EXPECT_EQ(hdr_at(*hdr, x, 0), expected) << "column " << x;
            if (!with_environment) {
                EXPECT_EQ((*display)[4 * x], 0) << "column " << x;
            }
        }
    }
}

TEST_F(BackgroundRender, SkyMatchesTheCpuPreethamModelAndShowsTheSun) {
    auto environment = std::make_shared<Environment>();
    environment->sky = SkyParameters{30.0f, 60.0f, 3.0f};
    environment->intensity = 0.5f;
    const glm::dvec3 sun = sun_direction(*environment->sky);
    const Scene scene = ground_scene(false);
    auto renderer = test::create_renderer(*context_, scene, nullptr);
    ASSERT_TRUE(renderer) << renderer.error();
    ASSERT_TRUE((*renderer)->set_environment(environment));
    const glm::vec3 eye(0, 1, 0);
    // The centre pixel looks at the sun; the frame lies above the horizon.
    const RenderSettings settings = looking(eye, eye + glm::vec3(sun));
    ASSERT_TRUE((*renderer)->render(settings));
    auto hdr = (*renderer)->read_hdr();
    ASSERT_TRUE(hdr);
    auto expected = [&](uint32_t x, uint32_t y) {
        const glm::dvec3 d = pinhole_ray(settings.camera, x, y);
        glm::dvec3 radiance = sky_radiance(*environment->sky, d);
        if (glm::dot(d, sun) >= std::cos(sun_angular_radius())) radiance += sun_disc_radiance(*environment->sky);
        return radiance * double(environment->intensity);
    };
    const uint32_t centre = kSize / 2;
    for (auto [x, y] : {std::pair{0u, 0u}, {kSize - 1, 0u}, {0u, kSize - 1}, {kSize - 1, kSize - 1},
                        {5u, 20u}, {centre, 2u}, {centre, centre}}) {
        const glm::dvec3 cpu = expected(x, y);
        const glm::vec3 gpu = hdr_at(*hdr, x, y);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(gpu[ch], cpu[ch], 2e-3 * cpu[ch] + 1e-6) << "pixel " << x << "," << y << " channel " << ch;
    }
    // The sun's disc is far brighter than the sky beside it.
    EXPECT_GT(hdr_at(*hdr, centre, centre).g, 100.0f * hdr_at(*hdr, centre, 2).g);
}

TEST_F(BackgroundRender, RotationTurnsTheBackgroundWithTheLight) {
    // A dim map with a bright patch beside +X (u < 1/16, 11 to 34 degrees up);
    // turned by 90 degrees it lies beside +Z.
    auto environment = std::make_shared<Environment>();
    environment->map = EquirectMap{64, 32, std::vector<glm::vec3>(64 * 32, glm::vec3(0.02f))};
    const glm::vec3 patch(50.0f);
    for (uint32_t y = 10; y < 14; ++y)
        for (uint32_t x = 0; x < 4; ++x) environment->map.texels[y * 64 + x] = patch;
    environment->rotation_deg = 90.0f;
    const LightTree tree = environment_tree(*environment, 512);
    const Scene scene = ground_scene(true);
    auto renderer = test::create_renderer(*context_, scene, &tree);
    ASSERT_TRUE(renderer) << renderer.error();
    ASSERT_TRUE((*renderer)->set_environment(environment));

    // The box's face towards +Z is lit by the patch; the face towards -Z is not.
    auto face_radiance = [&](float side) {
        const RenderSettings settings = looking({0, 0.5f, 4 * side}, {0, 0.5f, 0});
        EXPECT_TRUE((*renderer)->render(settings));
        auto g = (*renderer)->read_gbuffer();
        auto hdr = (*renderer)->read_hdr();
        EXPECT_TRUE(g && hdr);
        double sum = 0.0;
        size_t count = 0;
        for (size_t i = 0; g && hdr && i < size_t(kSize) * kSize; ++i) {
            if (g->position[4 * i + 3] == 0.0f || std::abs(g->normal[4 * i + 2] - side) > 1e-3f) continue;
            sum += (*hdr)[4 * i + 1];
            ++count;
        }
        EXPECT_GT(count, 20u);
        return count ? sum / double(count) : 0.0;
    };
    EXPECT_GT(face_radiance(1.0f), 5.0 * face_radiance(-1.0f));

    // The background shows the patch on the same side: the centre of a view
    // from above the box towards it (phi 101.25 degrees, 22.5 degrees up).
    const double phi = (90.0 + 11.25) * std::numbers::pi / 180.0;
    const double up = 22.5 * std::numbers::pi / 180.0;
    const glm::vec3 towards(std::cos(up) * std::cos(phi), std::sin(up), std::cos(up) * std::sin(phi));
    const glm::vec3 eye(0, 2, 0);
    for (float side : {1.0f, -1.0f}) {
        const glm::vec3 d(side * towards.x, towards.y, side * towards.z);
        ASSERT_TRUE((*renderer)->render(looking(eye, eye + d)));
        auto hdr = (*renderer)->read_hdr();
        ASSERT_TRUE(hdr);
        EXPECT_EQ(hdr_at(*hdr, kSize / 2, kSize / 2), side > 0.0f ? patch : glm::vec3(0.02f));
    }
}

}  // namespace
}  // namespace lc::client
