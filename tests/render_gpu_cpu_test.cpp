// The GPU renderer against the CPU evaluator (double precision) at the very
// points the G-buffer holds: reference and lightcuts-radius radiance, cut
// sizes and hashes, tone mapping, cut visualisation, non-finite handling, and
// zero validation messages.
//
// Tolerance: |gpu - cpu| <= 1e-4 |cpu| + 1e-6 max|cpu| per channel. The GPU
// sums up to a few thousand float terms whose own error is ~1e-7 relative (we
// measure ~1e-5 at worst); 1e-4 leaves room for that and still fails on any
// formula difference (a 0.1% change of the range window fails it).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <span>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "editor_client/render/renderer.h"
#include "lightcuts/tone_mapping.h"
#include "lightmass_server/builders/tree_builder.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

constexpr uint32_t kSize = 64;

struct Comparison {
    size_t geometry_pixels = 0;
    size_t compared = 0;
    size_t boundary_exempt = 0;
    double max_relative = 0.0;
};

glm::dvec3 emissive_at(const GBufferReadback& g, size_t i) {
    return {g.emissive[4 * i], g.emissive[4 * i + 1], g.emissive[4 * i + 2]};
}

// True when p sits within float rounding of some node's influence sphere, where
// float and double may legitimately pick different cuts.
bool near_radius_boundary(const WalkTree& tree, const SurfacePoint& p) {
    for (int32_t i = 0; i < int32_t(tree.nodes.size()); ++i) {
        const GpuTreeNode& n = tree.node(i);
        if (n.radius < 0.0f || is_leaf(n)) continue;
        double d = glm::length(p.position - glm::dvec3(tree.light_of(i).position));
        if (std::abs(d - n.radius) <= 1e-4 * std::max(1.0, double(n.radius))) return true;
    }
    return false;
}

class GpuVsCpu : public ::testing::Test {
protected:
    void SetUp() override {
        LC_REQUIRE_VULKAN(context_);
        scene_ = test::make_floor_scene();
        // Lights of every type, some with ranges, coloured, above the floor and
        // in front of the wall; one classic light.
        scene_.lights = {
            test::point_light({-2.0f, 1.0f, 1.0f}, {1.0f, 0.9f, 0.8f}, 6.0f),
            test::point_light({-1.5f, 1.2f, 1.5f}, {0.2f, 0.4f, 1.0f}, 4.0f, 3.5f),
            test::point_light({2.5f, 0.8f, -1.0f}, {1.0f, 0.3f, 0.2f}, 5.0f, 4.0f),
            test::point_light({3.0f, 1.5f, 2.0f}, {0.9f, 1.0f, 0.5f}, 3.0f),
            test::point_light({0.0f, 2.0f, -4.0f}, {1.0f, 1.0f, 1.0f}, 8.0f, 6.0f),
            test::spot_light({0.0f, 3.0f, 1.0f}, {0.2f, -1.0f, -0.3f}, {1.0f, 0.8f, 0.4f}, 30.0f,
                             0.2f, 0.5f),
            test::spot_light({-3.0f, 2.5f, -2.0f}, {0.5f, -1.0f, 0.2f}, {0.4f, 1.0f, 0.6f}, 20.0f,
                             0.1f, 0.7f, 6.0f),
            test::directional_light({0.3f, -1.0f, -0.4f}, {0.2f, 0.2f, 0.25f}, 0.3f),
            test::oriented_light({1.0f, 2.5f, 0.5f}, {-0.3f, -1.0f, 0.2f}, {0.8f, 0.9f, 1.0f}, 9.0f),
            test::oriented_light({1.5f, 2.5f, 0.0f}, {0.2f, -1.0f, -0.4f}, {1.0f, 0.7f, 0.5f}, 7.0f),
        };
        for (uint32_t i = 0; i < scene_.lights.size(); ++i)
            test::set_unit_guid(scene_.lights[i], i);
        SceneLight classic = test::point_light({1.0f, 0.7f, 3.0f}, {0.6f, 1.0f, 0.6f}, 2.0f);
        classic.classic = true;
        test::set_unit_guid(classic, 100);
        scene_.lights.push_back(classic);

        settings_.width = settings_.height = kSize;
        settings_.camera = test::floor_camera();
    }

    void TearDown() override {
        if (context_) {
            EXPECT_EQ(context_->validation_message_count(), 0u);
        }
    }

    std::vector<SceneLight> tree_lights() const {
        std::vector<SceneLight> out;
        for (const SceneLight& l : scene_.lights)
            if (!l.classic) out.push_back(l);
        return out;
    }
    std::vector<SceneLight> classic_lights() const {
        std::vector<SceneLight> out;
        for (const SceneLight& l : scene_.lights)
            if (l.classic) out.push_back(l);
        return out;
    }

    // Renders, then compares every geometry pixel with `expected(p)`; when
    // `tree` is given, cut sizes and hashes must match the CPU's too.
    template <typename Expected>
    Comparison render_and_compare(Renderer& renderer, const RenderSettings& settings, Expected expected,
                                  const WalkTree* cut_tree = nullptr) {
        Comparison c;
        Result<RenderStats> stats = renderer.render(settings);
        EXPECT_TRUE(stats.ok()) << stats.error();
        if (!stats.ok()) return c;
        EXPECT_EQ(stats->nonfinite_pixels, 0u);
        Result<GBufferReadback> g = renderer.read_gbuffer();
        Result<std::vector<float>> hdr = renderer.read_hdr();
        Result<std::vector<uint32_t>> cuts = renderer.read_cuts();
        EXPECT_TRUE(g.ok() && hdr.ok() && cuts.ok());
        if (!g.ok() || !hdr.ok() || !cuts.ok()) return c;

        std::vector<glm::dvec3> cpu(kSize * kSize, glm::dvec3(0.0));
        std::vector<CutResult> cpu_cuts(kSize * kSize);
        double max_cpu = 0.0;
        for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
            if (g->position[4 * i + 3] == 0.0f) continue;
            ++c.geometry_pixels;
            SurfacePoint p = test::gbuffer_point(*g, i);
            cpu_cuts[i] = expected(p);
            cpu[i] = cpu_cuts[i].radiance + emissive_at(*g, i);
            max_cpu = std::max({max_cpu, cpu[i].x, cpu[i].y, cpu[i].z});
        }
        EXPECT_EQ(stats->geometry_pixels, c.geometry_pixels);
        EXPECT_GT(max_cpu, 0.0) << "the test scene renders black";
        for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
            const float* gpu = &(*hdr)[4 * i];
            if (g->position[4 * i + 3] == 0.0f) {
                // Background is black.
                EXPECT_EQ(gpu[0], 0.0f);
                EXPECT_EQ(gpu[1], 0.0f);
                EXPECT_EQ(gpu[2], 0.0f);
                continue;
            }
            if (cut_tree != nullptr && ((*cuts)[2 * i] != cpu_cuts[i].cut_size ||
                                        (*cuts)[2 * i + 1] != cpu_cuts[i].cut_hash)) {
                SurfacePoint p = test::gbuffer_point(*g, i);
                EXPECT_TRUE(near_radius_boundary(*cut_tree, p))
                    << "pixel " << i << ": GPU cut (" << (*cuts)[2 * i] << ", "
                    << (*cuts)[2 * i + 1] << ") vs CPU (" << cpu_cuts[i].cut_size << ", "
                    << cpu_cuts[i].cut_hash << ") away from any radius boundary";
                ++c.boundary_exempt;
                continue;
            }
            for (int ch = 0; ch < 3; ++ch) {
                double want = cpu[i][ch];
                double err = std::abs(double(gpu[ch]) - want);
                EXPECT_LE(err, 1e-4 * std::abs(want) + 1e-6 * max_cpu)
                    << "pixel " << i % kSize << "," << i / kSize << " channel " << ch << ": gpu "
                    << gpu[ch] << " cpu " << want;
                if (std::abs(want) > 1e-6 * max_cpu)
                    c.max_relative = std::max(c.max_relative, err / std::abs(want));
            }
            ++c.compared;
        }
        std::printf(
            "  %zu geometry pixels, %zu compared, %zu near a radius boundary, max relative "
            "error %.3g\n",
            c.geometry_pixels, c.compared, c.boundary_exempt, c.max_relative);
        return c;
    }

    std::unique_ptr<vk::Context> context_;
    Scene scene_;
    RenderSettings settings_;
};

TEST_F(GpuVsCpu, ReferenceWithoutTreeMatchesSceneLights) {
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene_, nullptr);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kReference;
    std::vector<SceneLight> lights = scene_.lights;  // tree lights and classic alike
    Comparison c = render_and_compare(**renderer, settings_, [&](const SurfacePoint& p) {
        CutResult r;
        r.radiance = shade_reference(lights, p);
        return r;
    });
    EXPECT_GT(c.geometry_pixels, kSize * kSize / 2);
    EXPECT_EQ(c.compared, c.geometry_pixels);
    RecordProperty("max_relative_error", std::to_string(c.max_relative));
    EXPECT_LT(c.max_relative, 1e-4);
}

TEST_F(GpuVsCpu, ReferenceAndLightcutsWithHandMadeTree) {
    const LightTree imported = test::make_pairing_tree(tree_lights());
    ASSERT_EQ(imported.leaf_count, tree_lights().size());
    const WalkTree tree = test::walk_tree(imported);
    Result<std::unique_ptr<Renderer>> renderer = Renderer::create(*context_, scene_, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    std::vector<SceneLight> classic = classic_lights();

    settings_.mode = RenderMode::kReference;
    Comparison ref = render_and_compare(**renderer, settings_, [&](const SurfacePoint& p) {
        CutResult r;
        r.radiance = shade_tree_leaves(tree, p) + shade_reference(classic, p);
        return r;
    });
    EXPECT_EQ(ref.compared, ref.geometry_pixels);

    settings_.mode = RenderMode::kLightcuts;
    CutSettings radius;
    radius.criterion = CutCriterion::kRadius;
    Comparison cuts = render_and_compare(
        **renderer, settings_,
        [&](const SurfacePoint& p) { return shade_lightcuts(tree, classic, p, radius); }, &tree);
    EXPECT_GT(cuts.compared, cuts.geometry_pixels * 99 / 100);
    EXPECT_LT(cuts.max_relative, 1e-4);
}

TEST_F(GpuVsCpu, LightcutsWithBuilderTreeAndRanges) {
    // More lights with ranges, so the radius criterion picks many different cuts.
    std::vector<SceneLight> lights;
    uint32_t index = 0;
    for (int x = -4; x <= 4; x += 2) {
        for (int z = -4; z <= 4; z += 2) {
            float fx = float(x), fz = float(z);
            SceneLight l = test::point_light({fx + 0.3f, 0.6f + 0.1f * float(index % 5), fz},
                                             {0.5f + 0.1f * float(index % 5), 0.8f, 1.0f},
                                             2.0f + float(index % 3), 2.0f + float(index % 4));
            test::set_unit_guid(l, index++);
            lights.push_back(l);
        }
    }
    scene_.lights = lights;
    bake::BuildOptions options;
    options.builder = BuilderKind::kOptimalPair;
    Result<bake::BuildResult> built = bake::build_light_tree(lights, options, nullptr);
    ASSERT_TRUE(built.ok()) << built.error();
    const WalkTree tree = test::walk_tree(built->tree);
    Result<std::unique_ptr<Renderer>> renderer = Renderer::create(*context_, scene_, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();

    settings_.mode = RenderMode::kLightcuts;
    CutSettings radius;
    Comparison c = render_and_compare(
        **renderer, settings_,
        [&](const SurfacePoint& p) { return shade_lightcuts(tree, {}, p, radius); }, &tree);
    EXPECT_GT(c.compared, c.geometry_pixels * 99 / 100);

    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_GT(stats->cuts.max_cut, 1u);
    EXPECT_LT(stats->cuts.avg_cut, double(lights.size()));
}

TEST_F(GpuVsCpu, ChainTreeOfDepthNIsWalkedWithoutAStack) {
    // A degenerate chain: each internal node has one leaf and the rest of the
    // chain, depth ~N. Radii shrink along the chain, so the walk stops at
    // different depths at different pixels.
    constexpr int kLeaves = 3000;
    LightTree tree;
    tree.nodes.resize(2 * kLeaves - 1);
    for (int k = 0; k < kLeaves - 1; ++k) {
        LightTreeNode& spine = tree.nodes[2 * k];
        spine.left = 2 * k + 1;
        spine.right = 2 * k + 2;
    }
    // Leaves: odd indices and the last node.
    std::vector<int> leaves;
    for (int k = 0; k < kLeaves - 1; ++k) leaves.push_back(2 * k + 1);
    leaves.push_back(2 * kLeaves - 2);
    for (size_t j = 0; j < leaves.size(); ++j) {
        LightTreeNode& leaf = tree.nodes[leaves[j]];
        float t = float(j) / float(leaves.size());
        leaf.position = {-4.0f + 8.0f * t, 0.5f + 0.5f * t, 2.0f - 4.0f * t};
        leaf.intensity = glm::vec3(0.01f, 0.008f, 0.006f);
        leaf.brightness = 0.01f;
        leaf.representative = leaves[j];
        leaf.radius = kUnboundedRadius;
    }
    // Spine nodes from the bottom up: sums and an influence radius around the
    // representative (the left leaf) that encloses the rest of the chain.
    for (int k = kLeaves - 2; k >= 0; --k) {
        LightTreeNode& spine = tree.nodes[2 * k];
        const LightTreeNode& left = tree.nodes[2 * k + 1];
        const LightTreeNode& right = tree.nodes[2 * k + 2];
        spine.position = left.position;
        spine.representative = 2 * k + 1;
        spine.intensity = left.intensity + right.intensity;
        spine.brightness = left.brightness + right.brightness;
        spine.radius = 0.2f + 6.0f * float(kLeaves - 1 - k) / float(kLeaves);
    }
    tree.leaf_count = kLeaves;
    const WalkTree walk = test::walk_tree(tree);
    scene_.lights.clear();
    Result<std::unique_ptr<Renderer>> renderer = Renderer::create(*context_, scene_, &walk);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    EXPECT_EQ((*renderer)->tree_depth(), uint32_t(kLeaves - 1));

    settings_.mode = RenderMode::kLightcuts;
    settings_.width = settings_.height = kSize;
    CutSettings radius;
    Comparison c = render_and_compare(
        **renderer, settings_, [&](const SurfacePoint& p) { return shade_lightcuts(walk, {}, p, radius); },
        &walk);
    EXPECT_GT(c.compared, c.geometry_pixels * 99 / 100);
    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    // Deep walks happen: some pixels need hundreds of chain steps.
    EXPECT_GT(stats->cuts.max_cut, 100u);
}

TEST_F(GpuVsCpu, ToneMappedDisplayMatchesTheCpuCurve) {
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene_, nullptr);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kReference;
    settings_.exposure = 2.5f;
    ASSERT_TRUE((*renderer)->render(settings_).ok());
    Result<std::vector<float>> hdr = (*renderer)->read_hdr();
    Result<std::vector<uint8_t>> display = (*renderer)->read_display();
    ASSERT_TRUE(hdr.ok() && display.ok());
    int max_diff = 0;
    size_t saturated = 0, mid = 0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
        for (int ch = 0; ch < 3; ++ch) {
            int want = tone::to_display_byte((*hdr)[4 * i + ch], settings_.exposure);
            int got = (*display)[4 * i + ch];
            max_diff = std::max(max_diff, std::abs(want - got));
            if (got == 255) ++saturated;
            if (got > 20 && got < 235) ++mid;
        }
        EXPECT_EQ((*display)[4 * i + 3], 255);
    }
    EXPECT_LE(max_diff, 1);
    EXPECT_GT(mid, saturated);  // the exposure leaves most of the image in range
}

TEST_F(GpuVsCpu, CutsAndCutSizeVisualisation) {
    std::vector<SceneLight> lights = tree_lights();
    for (SceneLight& l : lights)
        if (l.type != LightType::kDirectional && l.range == 0.0f) l.range = 3.0f;
    scene_.lights = lights;
    LightTree tree = test::make_pairing_tree(lights);
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene_, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();

    settings_.mode = RenderMode::kCuts;
    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    Result<std::vector<uint8_t>> display = (*renderer)->read_display();
    Result<std::vector<uint32_t>> cuts = (*renderer)->read_cuts();
    Result<GBufferReadback> g = (*renderer)->read_gbuffer();
    ASSERT_TRUE(display.ok() && cuts.ok() && g.ok());
    // Same cut, same colour; background black; several distinct cuts.
    std::map<uint32_t, std::array<uint8_t, 3>> colour_of;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
        std::array<uint8_t, 3> rgb{(*display)[4 * i], (*display)[4 * i + 1], (*display)[4 * i + 2]};
        if (g->position[4 * i + 3] == 0.0f) {
            EXPECT_EQ(rgb, (std::array<uint8_t, 3>{0, 0, 0}));
            continue;
        }
        auto [it, inserted] = colour_of.emplace((*cuts)[2 * i + 1], rgb);
        if (!inserted) {
            EXPECT_EQ(it->second, rgb) << "cut " << it->first;
        }
    }
    EXPECT_GE(colour_of.size(), 3u);
    std::set<std::array<uint8_t, 3>> distinct;
    for (auto& [hash, rgb] : colour_of) distinct.insert(rgb);
    EXPECT_EQ(distinct.size(), colour_of.size()) << "two cuts share a colour";

    settings_.mode = RenderMode::kCutSize;
    stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    display = (*renderer)->read_display();
    cuts = (*renderer)->read_cuts();
    ASSERT_TRUE(display.ok() && cuts.ok());
    uint32_t max_cut = 0;
    for (size_t i = 0; i < cuts->size(); i += 2) max_cut = std::max(max_cut, (*cuts)[i]);
    EXPECT_EQ(stats->cuts.max_cut, max_cut);
    EXPECT_GT(max_cut, 1u);
    // The scale bar: the bottom row runs from the low end to the high end of the ramp.
    const size_t bottom = size_t(kSize - 1) * kSize;
    const uint8_t* left = &(*display)[4 * bottom];
    const uint8_t* right = &(*display)[4 * (bottom + kSize - 1)];
    EXPECT_GT(left[2], left[0]);    // dark blue
    EXPECT_GT(right[0], right[2]);  // red
    // Pixels with equal cut sizes share a colour above the bar.
    std::map<uint32_t, std::array<uint8_t, 3>> by_size;
    for (size_t i = 0; i < size_t(kSize - kScaleBarRows) * kSize; ++i) {
        if (g->position[4 * i + 3] == 0.0f) continue;
        std::array<uint8_t, 3> rgb{(*display)[4 * i], (*display)[4 * i + 1], (*display)[4 * i + 2]};
        auto [it, inserted] = by_size.emplace((*cuts)[2 * i], rgb);
        if (!inserted) {
            EXPECT_EQ(it->second, rgb);
        }
    }
}

TEST_F(GpuVsCpu, NonFiniteRadianceIsCountedAndWrittenAsZero) {
    // A finite but huge intensity next to the floor overflows float: the pass
    // must count those pixels and write 0, never Inf.
    scene_.lights = {test::point_light({0.0f, 0.001f, 0.0f}, {1, 1, 1}, 3.0e38f)};
    test::set_unit_guid(scene_.lights[0], 0);
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene_, nullptr);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kReference;
    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_GT(stats->nonfinite_pixels, 0u);
    Result<std::vector<float>> hdr = (*renderer)->read_hdr();
    ASSERT_TRUE(hdr.ok());
    size_t zeros = 0;
    for (size_t i = 0; i < hdr->size(); ++i) ASSERT_TRUE(std::isfinite((*hdr)[i])) << i;
    for (size_t i = 0; i < hdr->size(); i += 4)
        if ((*hdr)[i] == 0.0f && (*hdr)[i + 3] == 1.0f) ++zeros;
    EXPECT_GE(zeros, stats->nonfinite_pixels);
}

TEST_F(GpuVsCpu, BadInputIsRefusedWithAMessage) {
    scene_.lights[0].intensity = std::nanf("");
    Result<std::unique_ptr<Renderer>> bad_light = test::create_renderer(*context_, scene_, nullptr);
    ASSERT_FALSE(bad_light.ok());
    EXPECT_FALSE(bad_light.error().empty());

    scene_.lights[0].intensity = 1.0f;
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene_, nullptr);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kLightcuts;
    Result<RenderStats> no_tree = (*renderer)->render(settings_);
    ASSERT_FALSE(no_tree.ok());
    EXPECT_NE(no_tree.error().find("needs a light tree"), std::string::npos) << no_tree.error();

    scene_.meshes[0].indices.push_back(999);
    scene_.meshes[0].indices.push_back(0);
    scene_.meshes[0].indices.push_back(1);
    Result<std::unique_ptr<Renderer>> bad_mesh = test::create_renderer(*context_, scene_, nullptr);
    ASSERT_FALSE(bad_mesh.ok());
    EXPECT_NE(bad_mesh.error().find("mesh 0"), std::string::npos) << bad_mesh.error();
}

TEST_F(GpuVsCpu, EmptySceneAndZeroLightsRenderBlack) {
    Scene empty;
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, empty, nullptr);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_EQ(stats->geometry_pixels, 0u);

    scene_.lights.clear();
    LightTree no_lights;
    renderer = test::create_renderer(*context_, scene_, &no_lights);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    for (RenderMode mode : {RenderMode::kReference, RenderMode::kLightcuts, RenderMode::kCutSize}) {
        settings_.mode = mode;
        stats = (*renderer)->render(settings_);
        ASSERT_TRUE(stats.ok()) << stats.error();
        EXPECT_EQ(stats->nonfinite_pixels, 0u);
        Result<std::vector<float>> hdr = (*renderer)->read_hdr();
        ASSERT_TRUE(hdr.ok());
        for (size_t i = 0; i < hdr->size(); i += 4) ASSERT_EQ((*hdr)[i], 0.0f);
    }
}

TEST_F(GpuVsCpu, TexturedEmissiveSurfaceDecodesSrgb) {
    // One texture, uniform colour (filtering cannot change it), on both the
    // base colour and the emissive slot.
    Texture texture;
    texture.width = texture.height = 4;
    for (int i = 0; i < 16; ++i) texture.rgba8.insert(texture.rgba8.end(), {200, 100, 50, 255});
    scene_.textures = {texture};
    scene_.materials[0].base_color_texture = 0;
    scene_.materials[0].emissive_texture = 0;
    scene_.materials[0].emissive_factor = {0.5f, 0.5f, 0.5f};
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene_, nullptr);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    EXPECT_TRUE((*renderer)->effects().textures);
    EXPECT_TRUE((*renderer)->effects().emissive);
    settings_.mode = RenderMode::kReference;
    std::vector<SceneLight> lights = scene_.lights;
    Comparison c = render_and_compare(**renderer, settings_, [&](const SurfacePoint& p) {
        CutResult r;
        r.radiance = shade_reference(lights, p);
        return r;
    });
    EXPECT_EQ(c.compared, c.geometry_pixels);
    Result<GBufferReadback> g = (*renderer)->read_gbuffer();
    ASSERT_TRUE(g.ok());
    // A floor pixel: albedo = factor x decoded texel; emissive = 0.5 x decoded texel.
    const glm::vec3 decoded(tone::srgb_decode(200 / 255.0f), tone::srgb_decode(100 / 255.0f),
                            tone::srgb_decode(50 / 255.0f));
    size_t floor_pixels = 0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
        if (g->position[4 * i + 3] == 0.0f || g->normal[4 * i + 1] < 0.99f) continue;
        ++floor_pixels;
        for (int ch = 0; ch < 3; ++ch) {
            ASSERT_NEAR(g->albedo[4 * i + ch],
                        scene_.materials[0].base_color_factor[ch] * decoded[ch], 2e-3);
            ASSERT_NEAR(g->emissive[4 * i + ch], 0.5f * decoded[ch], 2e-3);
        }
    }
    EXPECT_GT(floor_pixels, 100u);
}

}  // namespace
}  // namespace lc::client
