// The glossy lobe end to end (material_model.h): the scene analysis turns it
// on only for materials that have one, the GPU's reference and bound cuts
// match the CPU evaluator on glossy dielectrics and metals (with a metallic-
// roughness texture), a highlight appears where the mirror direction meets a
// light, and lightcuts' error against the reference stays bounded.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "editor_client/render/analysis/error_stats.h"
#include "editor_client/render/renderer.h"
#include "editor_client/render/analysis/scene_effects.h"
#include "editor_client/scene/scene_generator.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

constexpr uint32_t kSize = 48;

const EffectDecision* find_decision(const SceneEffects& effects, const std::string& prefix) {
    for (const EffectDecision& d : effects.decisions)
        if (d.name.rfind(prefix, 0) == 0) return &d;
    return nullptr;
}

// The floor scene with a varnished floor (dielectric, roughness 0.3) and a
// brushed-metal wall whose roughness and metalness come from a 2x2 texture.
Scene glossy_floor_scene() {
    Scene scene = test::make_floor_scene();
    scene.materials[0].roughness = 0.3f;
    scene.materials[1].metallic = 1.0f;
    scene.materials[1].roughness = 1.0f;
    Texture mr;
    mr.width = mr.height = 2;
    mr.srgb = false;
    // G: roughness, B: metallic (texel values scale the factors).
    mr.rgba8 = {0, 115, 255, 255, 0, 140, 255, 255, 0, 128, 200, 255, 0, 102, 255, 255};
    scene.textures.push_back(mr);
    scene.materials[1].metallic_roughness_texture = 0;
    for (Mesh& mesh : scene.meshes) {
        mesh.uvs.clear();
        for (const glm::vec3& p : mesh.positions) mesh.uvs.push_back({p.x * 0.5f, p.y * 0.5f});
    }
    return scene;
}

std::vector<SceneLight> glossy_lights() {
    std::vector<SceneLight> lights;
    uint32_t index = 0;
    for (int x = -4; x <= 4; ++x) {
        for (int z = -4; z <= 3; ++z) {
            SceneLight l = test::point_light(
                {float(x) * 0.9f + 0.1f, 0.4f + 0.15f * float((x + z + 8) % 5), float(z) * 0.9f},
                {0.6f + 0.05f * float(index % 8), 0.8f, 1.0f - 0.05f * float(index % 5)}, 1.5f);
            test::set_unit_guid(l, index++);
            lights.push_back(l);
        }
    }
    SceneLight spot = test::spot_light({0.0f, 3.0f, 1.0f}, {0.2f, -1.0f, -0.3f},
                                       {1.0f, 0.8f, 0.4f}, 20.0f, 0.2f, 0.6f);
    test::set_unit_guid(spot, index++);
    lights.push_back(spot);
    return lights;
}

class Glossy : public ::testing::Test {
protected:
    void SetUp() override {
        LC_REQUIRE_VULKAN(context_);
        scene_ = glossy_floor_scene();
        scene_.lights = glossy_lights();
        settings_.width = settings_.height = kSize;
        settings_.camera = test::floor_camera();
        settings_.exposure = 1.0f;
    }
    void TearDown() override {
        if (context_) {
            EXPECT_EQ(context_->validation_message_count(), 0u);
        }
    }
    std::unique_ptr<vk::Context> context_;
    Scene scene_;
    RenderSettings settings_;
};

TEST(GlossyEffect, IsSimulatedOnlyWhenAMaterialHasALobe) {
    Scene rough = test::make_floor_scene();
    SceneEffects off = analyse_scene_effects(rough, nullptr);
    EXPECT_FALSE(off.specular);
    const EffectDecision* d = find_decision(off, "glossy reflection");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->reason.find("roughness 1"), std::string::npos) << d->reason;

    Scene varnished = test::make_floor_scene();
    varnished.materials[0].roughness = 0.4f;
    SceneEffects on = analyse_scene_effects(varnished, nullptr);
    EXPECT_TRUE(on.specular);
    EXPECT_NE(find_decision(on, "glossy reflection")->reason.find("1 drawn material"),
              std::string::npos);

    // A black metal has no F0: no lobe to simulate.
    Scene black = test::make_floor_scene();
    black.materials[0] = black.materials[1];
    black.materials[0].base_color_factor = {0, 0, 0, 1};
    black.materials[0].metallic = 1.0f;
    black.materials[0].roughness = 0.2f;
    black.materials[1].roughness = 1.0f;
    EXPECT_FALSE(analyse_scene_effects(black, nullptr).specular);

    // A metallic-roughness texture may lower the roughness anywhere.
    SceneEffects textured = analyse_scene_effects(glossy_floor_scene(), nullptr);
    EXPECT_TRUE(textured.specular);
    EXPECT_NE(find_decision(textured, "glossy reflection")->reason.find("texture"),
              std::string::npos);
}

TEST_F(Glossy, ReferenceMatchesTheCpuEvaluator) {
    WalkTree tree = test::walk_tree(test::agglomerative_tree(scene_.lights));
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene_, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kReference;
    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_EQ(stats->nonfinite_pixels, 0u);
    auto g = (*renderer)->read_gbuffer();
    auto hdr = (*renderer)->read_hdr();
    ASSERT_TRUE(g.ok() && hdr.ok());
    size_t compared = 0, glossy = 0, textured = 0;
    double max_relative = 0.0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
        if (g->position[4 * i + 3] == 0.0f) continue;
        const SurfacePoint p = test::gbuffer_point(*g, i);
        if (p.exponent > 0.0) ++glossy;
        // The wall's roughness and metalness come from its texture's G and B
        // (texels 0.40 .. 0.55 and 0.78 .. 1, linear), the floor's from its factors.
        const float roughness = g->normal[4 * i + 3], metallic = g->albedo[4 * i + 3];
        if (roughness != 0.3f) {
            EXPECT_GE(roughness, 0.39f);
            EXPECT_LE(roughness, 0.56f);
            EXPECT_GE(metallic, 0.77f);
            ++textured;
        }
        const glm::dvec3 want = shade_tree_leaves(tree, p);
        for (int ch = 0; ch < 3; ++ch) {
            const double err = std::abs(double((*hdr)[4 * i + ch]) - want[ch]);
            // pow() of a float near 1 to the power n ~ 500: a few 1e-5 relative.
            EXPECT_LE(err, 2e-4 * want[ch] + 1e-7) << "pixel " << i << " channel " << ch;
            if (want[ch] > 1e-6) max_relative = std::max(max_relative, err / want[ch]);
        }
        ++compared;
    }
    std::printf("  %zu pixels (%zu glossy), max relative error %.3g\n", compared, glossy,
                max_relative);
    EXPECT_GT(compared, kSize * kSize / 2);
    EXPECT_EQ(glossy, compared);  // the floor and the textured wall
    EXPECT_GT(textured, compared / 10);
}

TEST_F(Glossy, BoundCutsMatchTheCpuAndTheHighlightIsThere) {
    WalkTree tree = test::walk_tree(test::agglomerative_tree(scene_.lights));
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene_, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kLightcuts;
    settings_.criterion = CutCriterion::kBound;
    for (BoundSearch search : {BoundSearch::kWalk, BoundSearch::kHeap}) {
        SCOPED_TRACE(bound_search_name(search));
        settings_.bound_search = search;
        Result<RenderStats> stats = (*renderer)->render(settings_);
        ASSERT_TRUE(stats.ok()) << stats.error();
        EXPECT_EQ(stats->nonfinite_pixels, 0u);
        auto g = (*renderer)->read_gbuffer();
        auto hdr = (*renderer)->read_hdr();
        auto cuts = (*renderer)->read_cuts();
        ASSERT_TRUE(g.ok() && hdr.ok() && cuts.ok());
        CutSettings cut_settings;
        cut_settings.criterion = CutCriterion::kBound;
        cut_settings.error_ratio = settings_.error_ratio;
        cut_settings.max_cut = settings_.max_cut;
        cut_settings.search = search;
        size_t geometry = 0, same_cut = 0;
        double lobe_share = 0.0;
        for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
            if (g->position[4 * i + 3] == 0.0f) continue;
            ++geometry;
            SurfacePoint p = test::gbuffer_point(*g, i);
            const CutResult cpu = shade_lightcuts(tree, {}, p, cut_settings);
            // How much of the pixel is the lobe's: the same cut without it.
            SurfacePoint matte = p;
            matte.specular = glm::dvec3(0.0);
            const double without = shade_lightcuts(tree, {}, matte, cut_settings).radiance.y;
            if (cpu.radiance.y > 0.0) lobe_share = std::max(lobe_share, 1.0 - without / cpu.radiance.y);
            if ((*cuts)[2 * i] != cpu.cut_size || (*cuts)[2 * i + 1] != cpu.cut_hash) continue;
            ++same_cut;
            for (int ch = 0; ch < 3; ++ch) {
                const double want = cpu.radiance[ch];
                EXPECT_LE(std::abs(double((*hdr)[4 * i + ch]) - want), 1e-3 * want + 1e-9)
                    << "pixel " << i << " channel " << ch;
            }
        }
        EXPECT_GE(double(same_cut), 0.99 * double(geometry));
        // Somewhere the lobe carries most of the light: a highlight.
        EXPECT_GT(lobe_share, 0.5);
    }
}

TEST_F(Glossy, LightcutsErrorAgainstTheReferenceStaysBounded) {
    WalkTree tree = test::walk_tree(test::agglomerative_tree(scene_.lights));
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene_, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kReference;
    ASSERT_TRUE((*renderer)->render(settings_).ok());
    auto reference = (*renderer)->read_hdr();
    ASSERT_TRUE(reference.ok());
    settings_.mode = RenderMode::kLightcuts;
    settings_.criterion = CutCriterion::kBound;
    settings_.error_ratio = 0.02f;
    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    auto lightcuts = (*renderer)->read_hdr();
    ASSERT_TRUE(lightcuts.ok());
    Result<ErrorStats> measured = compute_error_stats(*lightcuts, *reference, kSize, kSize, 0.02);
    ASSERT_TRUE(measured.ok()) << measured.error();
    const ErrorStats& e = *measured;
    std::printf("  mean %.4f p99 %.4f avg cut %.1f of %zu lights\n", e.rel_err_mean, e.rel_err_p99,
                stats->cuts.avg_cut, scene_.lights.size());
    EXPECT_LT(e.rel_err_mean, 0.02);
    EXPECT_LT(e.rel_err_p99, 0.1);
    EXPECT_LT(stats->cuts.avg_cut, double(scene_.lights.size()));
}

}  // namespace
}  // namespace lc::client
