// The G-buffer cast as rays (RendererOptions::primary = kRays,
// shaders/primary_rays.comp) is the rasterised one: on the furnished room
// (untextured: every material a constant, some meshes without normals) the
// same pixels hold geometry, at the same positions and with the same
// camera-facing normals and materials, up to rounding; a pixel whose centre
// grazes a silhouette may see the other surface. Auto keeps raster on a CPU
// device, and a textured scene refuses rays with a clear error.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

#include "editor_client/render/gpu/primary_geometry.h"
#include "editor_client/render/renderer.h"
#include "editor_client/scene/scene_generator.h"
#include "render_test_support.h"

namespace lc {
namespace {

using client::PrimaryChoice;
using client::Renderer;
using client::RendererOptions;
using PrimaryRays = test::VulkanTest;

float distance4(const std::vector<float>& a, const std::vector<float>& b, size_t pixel, int channels) {
    float d = 0.0f;
    for (int c = 0; c < channels; ++c) d = std::max(d, std::abs(a[4 * pixel + c] - b[4 * pixel + c]));
    return d;
}

TEST_F(PrimaryRays, TheGBufferByRaysIsTheRasterisedOne) {
    const Scene scene = client::make_furnished_room_scene();
    client::RenderSettings settings;
    settings.width = 96;
    settings.height = 72;
    settings.camera = test::furnished_room_camera();
    const client::GBufferReadback raster = test::gbuffer_of(*context_, scene, PrimaryChoice::kRaster, settings);
    const client::GBufferReadback rays = test::gbuffer_of(*context_, scene, PrimaryChoice::kRays, settings);
    ASSERT_EQ(raster.position.size(), rays.position.size());
    const size_t pixels = size_t(settings.width) * settings.height;
    size_t geometry = 0, same_coverage = 0, same_surface = 0;
    for (size_t i = 0; i < pixels; ++i) {
        const bool a = raster.position[4 * i + 3] != 0.0f, b = rays.position[4 * i + 3] != 0.0f;
        geometry += a ? 1 : 0;
        same_coverage += a == b ? 1 : 0;
        if (!a || !b) continue;
        // On the same plane to 1 mm, and within a fraction of the pixel's
        // footprint (7 cm here, more at grazing angles) along it: lavapipe's
        // rasteriser snaps vertices to 1/16 of a pixel, the ray does not.
        // Normals and materials to rounding.
        const glm::vec3 n(raster.normal[4 * i], raster.normal[4 * i + 1], raster.normal[4 * i + 2]);
        const glm::vec3 d(rays.position[4 * i] - raster.position[4 * i],
                          rays.position[4 * i + 1] - raster.position[4 * i + 1],
                          rays.position[4 * i + 2] - raster.position[4 * i + 2]);
        const bool same = std::abs(glm::dot(d, n)) < 1e-3f && glm::length(d) < 0.05f &&
                          distance4(raster.normal, rays.normal, i, 4) < 1e-3f &&
                          distance4(raster.albedo, rays.albedo, i, 4) < 1e-5f &&
                          distance4(raster.emissive, rays.emissive, i, 4) < 1e-5f;
        same_surface += same ? 1 : 0;
    }
    std::printf("  %zu geometry pixels, %zu same coverage, %zu same surface\n", geometry, same_coverage,
                same_surface);
    EXPECT_GT(geometry, pixels / 2);
    EXPECT_GE(double(same_coverage), 0.995 * double(pixels));
    // The rest: centres on a silhouette, where the rasteriser's and the ray's rounding pick different sides.
    EXPECT_GE(double(same_surface), 0.98 * double(geometry));
}

TEST_F(PrimaryRays, TheRealtimeModeLightsAGBufferCastAsRays) {
    Scene scene = client::make_furnished_room_scene();
    scene.lights = test::room_lights(64, 4, client::LightTypeChoice::kPoint, 2.0f);
    const LightTree tree = test::agglomerative_tree(scene.lights);
    client::RenderSettings settings;
    settings.width = 48;
    settings.height = 32;
    settings.camera = test::furnished_room_camera();
    settings.mode = client::RenderMode::kRealtime;
    std::vector<float> images[2];
    for (PrimaryChoice primary : {PrimaryChoice::kRaster, PrimaryChoice::kRays}) {
        RendererOptions options;
        options.primary = primary;
        Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene, &tree, options);
        ASSERT_TRUE(renderer.ok()) << renderer.error();
        Result<client::RenderStats> stats = (*renderer)->render(settings);
        ASSERT_TRUE(stats.ok()) << stats.error();
        EXPECT_EQ(stats->primary, primary == PrimaryChoice::kRays ? "rays" : "raster");
        EXPECT_EQ(stats->nonfinite_pixels, 0u);
        images[primary == PrimaryChoice::kRays] = (*renderer)->read_hdr().value();
    }
    // The same draws at (nearly) the same points: the images agree but for a few pixels.
    size_t close = 0, lit = 0;
    for (size_t i = 0; i < images[0].size(); i += 4) {
        const float a = images[0][i] + images[0][i + 1] + images[0][i + 2];
        const float b = images[1][i] + images[1][i + 1] + images[1][i + 2];
        if (a <= 0.0f) continue;
        ++lit;
        close += std::abs(a - b) <= 0.05f * a ? 1 : 0;
    }
    EXPECT_GT(lit, images[0].size() / 8);
    EXPECT_GE(double(close), 0.9 * double(lit));
}

TEST_F(PrimaryRays, AutoKeepsRasterOnACpuDeviceAndTexturesRefuseRays) {
    Scene scene = client::make_furnished_room_scene();
    client::RenderSettings settings;
    settings.width = settings.height = 16;
    settings.camera = test::furnished_room_camera();
    settings.mode = client::RenderMode::kReference;
    Result<std::unique_ptr<Renderer>> renderer =
        test::create_renderer(*context_, scene, nullptr, RendererOptions{});
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    Result<client::RenderStats> stats = (*renderer)->render(settings);
    ASSERT_TRUE(stats.ok()) << stats.error();
    // Auto casts rays on a GPU alone: a CPU device rasterises fast.
    EXPECT_EQ(stats->primary, context_->physical().is_software() ? "raster" : "rays");
    // A base colour texture: only the raster pass samples it.
    Texture texture;
    texture.width = texture.height = 1;
    texture.rgba8 = {255, 0, 0, 255};
    scene.textures.push_back(texture);
    ASSERT_FALSE(scene.materials.empty());
    scene.materials[0].base_color_texture = 0;
    RendererOptions rays;
    rays.primary = PrimaryChoice::kRays;
    Result<std::unique_ptr<Renderer>> textured = test::create_renderer(*context_, scene, nullptr, rays);
    ASSERT_TRUE(textured.ok()) << textured.error();
    Result<client::RenderStats> refused = (*textured)->render(settings);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().find("texture"), std::string::npos) << refused.error();
}

}  // namespace
}  // namespace lc
