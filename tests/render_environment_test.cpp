// A uniform white environment (radiance L = 1) as the server's directional
// lights, rendered on lavapipe: an open plane receives pi L, uniformly; a
// vertical wall standing on a wide ground receives half the floor's
// irradiance, because the ground (kept as an occluder: lights come from
// below it) hides the lower half of the sky.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "editor_client/render/renderer.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

constexpr uint32_t kSize = 48;
constexpr double kPi = std::numbers::pi;

std::vector<SceneLight> uniform_environment_lights() {
    Environment environment;
    environment.map = EquirectMap{128, 64, std::vector<glm::vec3>(128 * 64, glm::vec3(1.0f))};
    auto sampled = bake::sample_environment(environment, 3000, 1);
    EXPECT_TRUE(sampled) << sampled.error();
    return sampled ? sampled->lights : std::vector<SceneLight>{};
}

// Irradiance (pi times radiance, green) at the geometry pixels whose normal is `normal`.
std::vector<double> irradiance_where(const GBufferReadback& g, const std::vector<float>& hdr, glm::vec3 normal) {
    std::vector<double> out;
    for (size_t i = 0; i < size_t(g.width) * g.height; ++i) {
        if (g.position[4 * i + 3] == 0.0f) continue;
        const glm::vec3 n(g.normal[4 * i], g.normal[4 * i + 1], g.normal[4 * i + 2]);
        if (glm::dot(n, normal) > 0.99f) out.push_back(kPi * hdr[4 * i + 1]);
    }
    return out;
}

double mean_of(const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x;
    return sum / double(v.size());
}

double variation_of(const std::vector<double>& v) {
    const double mean = mean_of(v);
    double sq = 0.0;
    for (double x : v) sq += (x - mean) * (x - mean);
    return std::sqrt(sq / double(v.size())) / mean;
}

class EnvironmentRender : public test::VulkanTest {
protected:
    // Irradiance at the open floor's pixels, or at the pixels of a wall
    // standing on the ground, under the environment's tree.
    std::vector<double> irradiance(bool wall, RenderMode mode) {
        const std::vector<SceneLight> lights = uniform_environment_lights();
        const LightTree tree = test::agglomerative_tree(lights);
        const Scene scene = ground_scene(wall);  // the renderer keeps a reference
        auto renderer = test::create_renderer(*context_, scene, &tree);
        EXPECT_TRUE(renderer) << renderer.error();
        if (!renderer) return {};
        EXPECT_TRUE((*renderer)->effects().shadows);
        RenderSettings settings;
        settings.mode = mode;
        settings.error_ratio = 0.005f;
        settings.width = settings.height = kSize;
        settings.camera.eye = wall ? glm::vec3(0.0f, 1.0f, 4.0f) : glm::vec3(0.0f, 3.0f, 3.0f);
        settings.camera.target = wall ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f);
        settings.camera.yfov = wall ? 0.45f : 0.8f;
        auto stats = (*renderer)->render(settings);
        EXPECT_TRUE(stats) << stats.error();
        auto g = (*renderer)->read_gbuffer();
        auto hdr = (*renderer)->read_hdr();
        EXPECT_TRUE(g && hdr);
        if (!g || !hdr) return {};
        std::vector<double> out = irradiance_where(*g, *hdr, wall ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0));
        EXPECT_GT(out.size(), kSize * kSize / 2);
        std::printf("  %s, %s: mean %.5f, variation %.5f\n", wall ? "wall" : "floor", render_mode_name(mode),
                    mean_of(out), variation_of(out));
        return out;
    }

    static Scene ground_scene(bool wall) {
        Scene scene;
        scene.materials = {test::white_lambert()};
        scene.meshes.push_back(test::make_quad({-200, 0, 200}, {400, 0, 0}, {0, 0, -400}, 0));
        if (wall) scene.meshes.push_back(test::make_quad({-1, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0));
        scene.bounds_min = {-200, 0, -200};
        scene.bounds_max = {200, 2, 200};
        return scene;
    }
};

TEST_F(EnvironmentRender, OpenFloorIsUniformAtPiL) {
    for (RenderMode mode : {RenderMode::kReference, RenderMode::kLightcuts}) {
        const std::vector<double> floor = irradiance(false, mode);
        ASSERT_FALSE(floor.empty());
        EXPECT_LT(variation_of(floor), 0.01);
        EXPECT_NEAR(mean_of(floor), kPi, 0.01 * kPi);
    }
}

TEST_F(EnvironmentRender, WallOnTheGroundGetsHalfTheFloorsIrradiance) {
    for (RenderMode mode : {RenderMode::kReference, RenderMode::kLightcuts}) {
        const std::vector<double> wall = irradiance(true, mode);
        const std::vector<double> floor = irradiance(false, mode);
        ASSERT_FALSE(wall.empty() || floor.empty());
        EXPECT_NEAR(mean_of(wall) / mean_of(floor), 0.5, 0.01);
    }
}

}  // namespace
}  // namespace lc::client
