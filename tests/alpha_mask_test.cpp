// alphaMode MASK: shadow rays pass where a masked surface is cut out (the CPU's
// ShadowBvh and the shaders' any-hit walk), and the G-buffer discards there.
//
// The scene: a floor, and 4 units above it a 2 x 2 quad whose base colour
// texture is an 8 x 8 checkerboard of alpha 0 and 255 (alphaCutoff 0.5). A
// directional light at 45 degrees throws the quad's shadow 4 units to +x, a
// parallel projection, so exactly half of the shadow's footprint is lit.
#include <gtest/gtest.h>

#include <cstdio>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "editor_client/render/renderer.h"
#include "editor_client/render/analysis/scene_effects.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/scene_generator.h"
#include "lightcuts/alpha_mask.h"
#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/occlusion/shadow_ray.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

constexpr int kCells = 8;
const glm::vec3 kLightTravel = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
// The shadow's footprint on the floor: x in [3, 5], z in [-1, 1].
constexpr float kFootprintLo = 3.0f, kFootprintHi = 5.0f, kFootprintHalfZ = 1.0f;

Texture checkerboard() {
    Texture t;
    t.width = t.height = kCells;
    t.rgba8.resize(size_t(kCells) * kCells * 4, 255);
    for (int y = 0; y < kCells; ++y)
        for (int x = 0; x < kCells; ++x) t.rgba8[size_t(y * kCells + x) * 4 + 3] = (x + y) % 2 ? 255 : 0;
    return t;
}

Scene masked_quad_scene(AlphaMode mode) {
    Scene scene;
    Material floor = test::white_lambert();
    Material mask = test::white_lambert();
    mask.alpha_mode = mode;
    mask.alpha_cutoff = 0.5f;
    mask.base_color_texture = 0;
    mask.double_sided = true;
    scene.materials = {floor, mask};
    scene.textures = {checkerboard()};
    scene.meshes.push_back(test::make_quad({-2, 0, 4}, {10, 0, 0}, {0, 0, -8}, 0));
    scene.meshes.push_back(test::make_quad({-1, 4, 1}, {2, 0, 0}, {0, 0, -2}, 1));
    scene.lights.push_back(test::directional_light(kLightTravel, glm::vec3(1.0f), 3.0f));
    test::set_unit_guid(scene.lights.back(), 0);
    scene.bounds_min = {-2, 0, -4};
    scene.bounds_max = {8, 4, 4};
    return scene;
}

bool in_footprint(const glm::vec3& p) {
    return p.x > kFootprintLo && p.x < kFootprintHi && std::abs(p.z) < kFootprintHalfZ;
}

double cpu_visibility(const ShadowBvh& bvh, double bias, const glm::vec3& floor_point) {
    return light_visibility(bvh, bias, LightType::kDirectional, glm::dvec3(0.0), glm::dvec3(kLightTravel),
                            glm::dvec3(floor_point), glm::dvec3(0, 1, 0));
}

TEST(AlphaMask, KeepThresholdMatchesTheFloatComparison) {
    EXPECT_EQ(mask_keep_threshold(1.0f, 0.5f), 128u);  // 127/255 < 0.5 <= 128/255
    EXPECT_EQ(mask_keep_threshold(1.0f, 0.0f), 0u);
    EXPECT_EQ(mask_keep_threshold(0.5f, 0.75f), kMaskKeepsNothing);
    for (uint32_t a = 0; a < 256; ++a) {
        const bool keeps = float(a) / 255.0f * 0.8f >= 0.3f;
        EXPECT_EQ(a >= mask_keep_threshold(0.8f, 0.3f), keeps) << a;
    }
}

TEST(AlphaMask, TexelsWrapAndRowZeroIsTheTop) {
    AlphaMask mask;
    mask.width = 2;
    mask.height = 2;
    mask.alpha = {10, 20, 30, 40};
    EXPECT_EQ(mask_texel(mask, {0.25f, 0.25f}), 10u);
    EXPECT_EQ(mask_texel(mask, {0.75f, 0.25f}), 20u);
    EXPECT_EQ(mask_texel(mask, {0.25f, 0.75f}), 30u);
    EXPECT_EQ(mask_texel(mask, {1.75f, -0.25f}), 40u);  // repeat
    EXPECT_EQ(mask_texel(mask, {1.0f, 1.0f}), 10u);
}

TEST(AlphaMask, MaterialsWithoutCutOutsCastSolidShadows) {
    Scene scene = masked_quad_scene(AlphaMode::kMask);
    EXPECT_TRUE(alpha_mask_of(scene, scene.materials[1]).has_value());
    EXPECT_FALSE(alpha_mask_of(scene, scene.materials[0]).has_value());  // OPAQUE
    Material untextured = scene.materials[1];
    untextured.base_color_texture = -1;
    EXPECT_FALSE(alpha_mask_of(scene, untextured).has_value());  // factor 1 keeps all
    untextured.base_color_factor.a = 0.25f;
    std::optional<AlphaMask> none = alpha_mask_of(scene, untextured);
    ASSERT_TRUE(none.has_value());
    EXPECT_TRUE(mask_cuts_everything(*none));
}

// The CPU test alone, on a dense grid over the footprint: half of it is lit.
TEST(AlphaMask, CpuShadowThroughCheckerboardMatchesTheAnalyticFraction) {
    const Scene scene = masked_quad_scene(AlphaMode::kMask);
    const ShadowBvh bvh = ShadowBvh::build(scene);
    EXPECT_EQ(bvh.stats().masked, 2u);
    const double bias = shadow_ray_bias(scene);
    constexpr int kSamples = 400;  // 50 per cell: pixel centres never meet a cell edge
    size_t lit = 0;
    for (int i = 0; i < kSamples; ++i) {
        for (int k = 0; k < kSamples; ++k) {
            const float x = kFootprintLo + (float(i) + 0.5f) * (kFootprintHi - kFootprintLo) / kSamples;
            const float z = -kFootprintHalfZ + (float(k) + 0.5f) * 2.0f * kFootprintHalfZ / kSamples;
            lit += cpu_visibility(bvh, bias, {x, 0.0f, z}) > 0.5;
        }
    }
    const double fraction = double(lit) / double(kSamples * kSamples);
    std::printf("  CPU: lit fraction %.4f behind the checkerboard (analytic 0.5)\n", fraction);
    EXPECT_NEAR(fraction, 0.5, 0.01 * 0.5);
    // The same quad opaque hides the whole footprint.
    const ShadowBvh solid = ShadowBvh::build(masked_quad_scene(AlphaMode::kOpaque));
    EXPECT_EQ(solid.stats().masked, 0u);
    EXPECT_EQ(cpu_visibility(solid, bias, {4.1f, 0.0f, 0.1f}), 0.0);
}

TEST(AlphaMask, EffectsReportNamesMaskAndBlend) {
    Scene scene = masked_quad_scene(AlphaMode::kMask);
    SceneEffects effects = analyse_scene_effects(scene, nullptr, ShadowMode::kOn);
    bool mask_named = false;
    for (const EffectDecision& d : effects.decisions)
        if (d.name.find("alphaMode MASK") != std::string::npos) mask_named = d.simulated;
    EXPECT_TRUE(mask_named);
    EXPECT_TRUE(effects.occluder_masks.any());
    scene.materials[1].alpha_mode = AlphaMode::kBlend;
    effects = analyse_scene_effects(scene, nullptr, ShadowMode::kOn);
    bool blend_named = false;
    for (const EffectDecision& d : effects.decisions)
        if (d.name.find("alphaMode BLEND") != std::string::npos)
            blend_named = d.reason.find("1 drawn material") != std::string::npos;
    EXPECT_TRUE(blend_named);
}

// add-lights --layout surface: lights on a masked surface stand only where
// its mask keeps it.
TEST(AlphaMask, SurfaceLightsStandOnlyWhereTheMaskKeepsTheSurface) {
    const Scene scene = masked_quad_scene(AlphaMode::kMask);
    LightLayoutOptions options;
    options.count = 400;
    options.layout = LightLayout::kSurface;
    options.seed = 7;
    options.surfaces = &scene;
    options.box_min = {-1.5f, 3.5f, -1.5f};  // the masked quad only
    options.box_max = {1.5f, 4.5f, 1.5f};
    Result<std::vector<SceneLight>> lights = generate_lights(options);
    ASSERT_TRUE(lights.ok()) << lights.error();
    ASSERT_EQ(lights->size(), 400u);
    const AlphaMask mask = *alpha_mask_of(scene, scene.materials[1]);
    for (const SceneLight& light : *lights) {
        const glm::vec2 uv((light.position.x + 1.0f) / 2.0f, (1.0f - light.position.z) / 2.0f);
        EXPECT_TRUE(mask_keeps(mask, uv)) << light.position.x << ", " << light.position.z;
    }
    // A mask that keeps nothing leaves no surface in the box.
    Scene cut = scene;
    cut.materials[1].base_color_texture = -1;
    cut.materials[1].base_color_factor.a = 0.1f;
    options.surfaces = &cut;
    EXPECT_FALSE(generate_lights(options).ok());
}

// The GPU: a frame looking straight down at the footprint (a plane seen
// square-on samples it uniformly: 10 x 10 pixels per cell), lit fraction
// within 1% of the analytic half, pixel for pixel as the CPU's BVH says.
TEST(AlphaMask, GpuShadowThroughCheckerboardMatchesTheAnalyticFraction) {
    std::string why;
    std::unique_ptr<vk::Context> context = test::make_headless_context(why);
    if (!context) GTEST_SKIP() << "no Vulkan device: " << why;
    const Scene scene = masked_quad_scene(AlphaMode::kMask);
    RendererOptions options;
    options.shadows = ShadowMode::kOn;
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context, scene, nullptr, options);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    RenderSettings settings;
    settings.width = settings.height = 128;
    settings.camera.eye = {4.0f, 10.0f, 0.0f};
    settings.camera.target = {4.0f, 0.0f, 0.0f};
    settings.camera.up = {0.0f, 0.0f, -1.0f};
    settings.camera.yfov = 2.0f * std::atan(1.6f / 10.0f);  // 3.2 units across the floor
    Result<RenderStats> stats = (*renderer)->render(settings);
    ASSERT_TRUE(stats.ok()) << stats.error();
    Result<std::vector<float>> hdr = (*renderer)->read_hdr();
    Result<GBufferReadback> g = (*renderer)->read_gbuffer();
    ASSERT_TRUE(hdr.ok() && g.ok());
    float brightest = 0.0f;
    for (size_t i = 0; i < hdr->size(); i += 4) brightest = std::max(brightest, (*hdr)[i]);
    ASSERT_GT(brightest, 0.0f);
    const double bias = shadow_ray_bias(scene);
    size_t inside = 0, lit = 0, agree = 0;
    for (size_t i = 0; i < size_t(g->width) * g->height; ++i) {
        const glm::vec3 p(g->position[4 * i], g->position[4 * i + 1], g->position[4 * i + 2]);
        if (g->position[4 * i + 3] != 1.0f || !in_footprint(p)) continue;
        ++inside;
        const bool gpu_lit = (*hdr)[4 * i] > 0.5f * brightest;
        lit += gpu_lit;
        agree += gpu_lit == (cpu_visibility((*renderer)->shadow_bvh(), bias, p) > 0.5);
    }
    EXPECT_GT(inside, 6000u);  // about 80 x 80 pixels
    std::printf("  GPU: lit fraction %.4f of %zu pixels behind the checkerboard (analytic 0.5), %zu agree with the CPU\n",
                double(lit) / double(inside), size_t(inside), size_t(agree));
    EXPECT_NEAR(double(lit) / double(inside), 0.5, 0.01 * 0.5) << lit << " of " << inside;
    EXPECT_GE(double(agree), 0.995 * double(inside));
    EXPECT_EQ(context->validation_message_count(), 0u);
}

// The texture coordinate of p on one of `mesh`'s triangles (within `tolerance`
// of its plane), or nothing.
std::optional<glm::vec2> uv_on_mesh(const Mesh& mesh, const glm::vec3& p, float tolerance) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t* c = &mesh.indices[t];
        const glm::dvec3 a(mesh.positions[c[0]]), b(mesh.positions[c[1]]), d(mesh.positions[c[2]]);
        const glm::dvec3 n = glm::cross(b - a, d - a);
        const double area2 = glm::dot(n, n);
        if (!(area2 > 0.0)) continue;
        const glm::dvec3 x(p);
        if (std::abs(glm::dot(x - a, n)) / std::sqrt(area2) > tolerance) continue;
        const double wb = glm::dot(glm::cross(x - a, d - a), n) / area2;
        const double wd = glm::dot(glm::cross(b - a, x - a), n) / area2;
        if (wb < 0.0 || wd < 0.0 || wb + wd > 1.0) continue;
        return mesh.uvs[c[0]] * float(1.0 - wb - wd) + mesh.uvs[c[1]] * float(wb) +
               mesh.uvs[c[2]] * float(wd);
    }
    return std::nullopt;
}

Result<GBufferReadback> gbuffer_of(const vk::Context& context, const Scene& scene,
                                   const RenderSettings& settings) {
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(context, scene, nullptr);
    if (!renderer) return make_error(renderer.error());
    Result<RenderStats> stats = (*renderer)->render(settings);
    if (!stats) return make_error(stats.error());
    return (*renderer)->read_gbuffer();
}

// Khronos' AlphaBlendModeTest: its three MASK quads (cutoffs 0.25, 0.5, 0.75
// over one label texture) are cut out where the CPU's mask says, pixel by
// pixel against the same frame with the masks made opaque; higher cutoffs cut
// out more; the OPAQUE quad keeps every pixel.
TEST(AlphaMask, AlphaBlendModeTestCutsOutItsMaskRow) {
    LC_REQUIRE_SHARED_SCENES();
    std::string why;
    std::unique_ptr<vk::Context> context = test::make_headless_context(why);
    if (!context) GTEST_SKIP() << "no Vulkan device: " << why;
    Result<Scene> loaded =
        load_scene(test::shared_scenes_dir() / "AlphaBlendModeTest" / "AlphaBlendModeTest.gltf");
    ASSERT_TRUE(loaded.ok()) << loaded.error();
    Scene masked = std::move(loaded).value();
    masked.lights.push_back(test::directional_light({0.0f, -0.3f, -1.0f}, glm::vec3(1.0f), 3.0f));
    test::set_unit_guid(masked.lights.back(), 0);
    Scene opaque = masked;
    std::vector<size_t> mask_meshes;
    for (size_t m = 0; m < masked.meshes.size(); ++m) {
        const int material = masked.meshes[m].material;
        if (material >= 0 && masked.materials[size_t(material)].alpha_mode == AlphaMode::kMask)
            mask_meshes.push_back(m);
    }
    ASSERT_EQ(mask_meshes.size(), 3u) << "the file's three MASK quads";
    for (Material& m : opaque.materials) m.alpha_mode = AlphaMode::kOpaque;

    RenderSettings settings;
    settings.width = 192;
    settings.height = 96;
    const glm::vec3 centre = 0.5f * (masked.bounds_min + masked.bounds_max);
    settings.camera.eye = centre + glm::vec3(0.0f, 0.0f, 8.0f);
    settings.camera.target = centre;
    settings.camera.yfov = 0.45f;
    Result<GBufferReadback> with_masks = gbuffer_of(*context, masked, settings);
    Result<GBufferReadback> without = gbuffer_of(*context, opaque, settings);
    ASSERT_TRUE(with_masks.ok() && without.ok());
    const float tolerance = 1e-3f * glm::length(masked.bounds_max - masked.bounds_min);
    std::vector<std::pair<float, double>> cut_by_cutoff;
    for (size_t m : mask_meshes) {
        const Mesh& mesh = masked.meshes[m];
        const AlphaMask mask = *alpha_mask_of(masked, masked.materials[size_t(mesh.material)]);
        size_t covered = 0, cut = 0, agree = 0;
        for (size_t i = 0; i < size_t(settings.width) * settings.height; ++i) {
            const float* q = &without->position[4 * i];
            const float* r = &with_masks->position[4 * i];
            if (q[3] != 1.0f) continue;
            const std::optional<glm::vec2> uv = uv_on_mesh(mesh, {q[0], q[1], q[2]}, tolerance);
            if (!uv) continue;
            ++covered;
            const bool drawn = r[3] == 1.0f && glm::length(glm::vec3(r[0], r[1], r[2]) -
                                                           glm::vec3(q[0], q[1], q[2])) < tolerance;
            cut += !drawn;
            agree += drawn == mask_keeps(mask, *uv);
        }
        SCOPED_TRACE("mesh " + std::to_string(m));
        ASSERT_GT(covered, 200u);
        // Linear filtering in the G-buffer against the nearest texel: edges may differ.
        EXPECT_GE(double(agree), 0.95 * double(covered));
        const double fraction = double(cut) / double(covered);
        EXPECT_GT(fraction, 0.05);
        EXPECT_LT(fraction, 0.95);
        cut_by_cutoff.emplace_back(masked.materials[size_t(mesh.material)].alpha_cutoff, fraction);
    }
    std::sort(cut_by_cutoff.begin(), cut_by_cutoff.end());
    for (size_t k = 1; k < cut_by_cutoff.size(); ++k)
        EXPECT_GT(cut_by_cutoff[k].second, cut_by_cutoff[k - 1].second);
    EXPECT_EQ(context->validation_message_count(), 0u);
}

}  // namespace
}  // namespace lc::client
