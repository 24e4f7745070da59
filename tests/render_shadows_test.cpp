// Shadows on the GPU (shaders/shadow_rays.glsl) against the CPU evaluator with
// the same occluders (ShadowBvh, in double): the reference, the bound
// criterion's walk and heap, the radius criterion, classic lights, and the
// reference split over several dispatches. Also: shadows are skipped where
// nothing can hide a light, forced on and off by the user, and counted.
//
// Tolerance: a shadow ray that grazes an edge may hit in float and miss in
// double, so a few pixels may differ; we require 99% of the geometry pixels
// within 1e-3 relative (the cut must match too, for lightcuts).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "editor_client/render/renderer.h"
#include "lightcuts/occlusion/shadow_ray.h"
#include "editor_client/scene/scene_generator.h"
#include "lightmass_server/builders/tree_builder.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

constexpr uint32_t kSize = 48;

double max_channel_of(const glm::dvec3& v) { return std::max({v.x, v.y, v.z}); }

std::vector<SceneLight> furnished_room_lights(uint32_t count, uint32_t seed) {
    std::vector<SceneLight> out = test::room_lights(count, seed, LightTypeChoice::kPoint, 4.0f);
    // One light under the table: only the floor beneath it sees it.
    SceneLight under = out.empty() ? SceneLight{} : out.front();
    under.position = {0.0f, 0.35f, 0.0f};
    under.intensity = 6.0f;
    test::set_unit_guid(under, 999);
    out.push_back(under);
    return out;
}

RenderCamera room_camera() {
    RenderCamera camera;
    camera.eye = {0.0f, 2.2f, 4.6f};
    camera.target = {0.0f, 0.4f, -1.0f};
    camera.yfov = 1.1f;
    return camera;
}

struct Agreement {
    size_t geometry = 0;
    size_t agree = 0;
    size_t shadowed = 0;  // pixels where the CPU's shadows remove light
    uint64_t shadow_rays = 0;
};

// Renders, then compares every geometry pixel with the CPU's frame:
// expected(g, shadowed) gives one CutResult per pixel, its points carrying the
// renderer's occluders when `shadowed`. `cuts_must_match` also requires the
// same cut size and hash.
template <typename ExpectedFrame>
Agreement compare(Renderer& renderer, const RenderSettings& settings, ExpectedFrame expected,
                  bool cuts_must_match) {
    Agreement a;
    Result<RenderStats> stats = renderer.render(settings);
    EXPECT_TRUE(stats.ok()) << stats.error();
    if (!stats.ok()) return a;
    EXPECT_EQ(stats->nonfinite_pixels, 0u);
    EXPECT_EQ(stats->cuts.loop_limit_stops, 0u);
    a.shadow_rays = stats->shadows.rays;
    Result<GBufferReadback> g = renderer.read_gbuffer();
    Result<std::vector<float>> hdr = renderer.read_hdr();
    Result<std::vector<uint32_t>> gpu_cuts = renderer.read_cuts();
    EXPECT_TRUE(g.ok() && hdr.ok() && gpu_cuts.ok());
    if (!g.ok() || !hdr.ok() || !gpu_cuts.ok()) return a;
    const std::vector<CutResult> shadowed = expected(*g, true);
    const std::vector<CutResult> open = expected(*g, false);
    for (size_t i = 0; i < size_t(settings.width) * settings.height; ++i) {
        if (g->position[4 * i + 3] == 0.0f) continue;
        ++a.geometry;
        const CutResult& cpu = shadowed[i];
        if (max_channel_of(open[i].radiance) > 1.001 * max_channel_of(cpu.radiance)) ++a.shadowed;
        if (cuts_must_match &&
            ((*gpu_cuts)[2 * i] != cpu.cut_size || (*gpu_cuts)[2 * i + 1] != cpu.cut_hash))
            continue;
        bool close = true;
        for (int ch = 0; ch < 3; ++ch) {
            const double want = cpu.radiance[ch];
            close = close && std::abs(double((*hdr)[4 * i + ch]) - want) <=
                                 1e-3 * std::abs(want) + 1e-7;
        }
        a.agree += close;
    }
    std::printf("  %zu geometry pixels, %zu agree, %zu shadowed, %llu shadow rays\n", a.geometry,
                a.agree, a.shadowed, static_cast<unsigned long long>(a.shadow_rays));
    return a;
}

// The point at pixel i, with the renderer's occluders when `shadowed`.
SurfacePoint point_at(const Renderer& renderer, const GBufferReadback& g, size_t i,
                      bool shadowed) {
    SurfacePoint p = test::gbuffer_point(g, i);
    if (shadowed) {
        p.occluders = &renderer.shadow_bvh();
        p.shadow_bias = renderer.shadow_bias();
    }
    return p;
}

// An expected frame from a per-pixel function of the surface point.
template <typename PerPixel>
auto per_pixel(const Renderer& renderer, PerPixel f) {
    return [&renderer, f](const GBufferReadback& g, bool shadowed) {
        std::vector<CutResult> out(size_t(g.width) * g.height);
        for (size_t i = 0; i < out.size(); ++i)
            if (g.position[4 * i + 3] != 0.0f) out[i] = f(point_at(renderer, g, i, shadowed));
        return out;
    };
}

// The CPU's exact sum over the tree's leaves (reference mode), as an expected frame.
auto leaves_frame(const Renderer& renderer, const WalkTree& tree) {
    return per_pixel(renderer, [&tree](const SurfacePoint& p) {
        CutResult r;
        r.radiance = shade_tree_leaves(tree, p);
        return r;
    });
}

class Shadows : public ::testing::Test {
protected:
    void SetUp() override {
        LC_REQUIRE_VULKAN(context_);
        scene_ = make_furnished_room_scene();
        scene_.lights = furnished_room_lights(40, 11);
        tree_ = test::walk_tree(test::agglomerative_tree(scene_.lights));
        settings_.width = settings_.height = kSize;
        settings_.camera = room_camera();
    }
    void TearDown() override {
        if (context_) {
            EXPECT_EQ(context_->validation_message_count(), 0u);
        }
    }
    std::unique_ptr<vk::Context> context_;
    Scene scene_;
    WalkTree tree_;
    RenderSettings settings_;
};

TEST_F(Shadows, ReferenceMatchesTheCpuWithTheSameOccluders) {
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene_, &tree_);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    ASSERT_TRUE((*renderer)->effects().shadows);
    settings_.mode = RenderMode::kReference;
    Agreement a = compare(**renderer, settings_, leaves_frame(**renderer, tree_), false);
    EXPECT_GE(a.agree, a.geometry * 99 / 100);
    EXPECT_GT(a.shadowed, a.geometry / 10) << "the furniture should shadow part of the view";
    EXPECT_GT(a.shadow_rays, 0u);
}

TEST_F(Shadows, BoundWalkAndHeapMatchTheCpu) {
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene_, &tree_);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kLightcuts;
    settings_.criterion = CutCriterion::kBound;
    settings_.error_ratio = 0.02f;
    settings_.max_cut = 64;
    for (BoundSearch search : {BoundSearch::kWalk, BoundSearch::kHeap}) {
        settings_.bound_search = search;
        CutSettings cut;
        cut.criterion = CutCriterion::kBound;
        cut.error_ratio = settings_.error_ratio;
        cut.max_cut = settings_.max_cut;
        cut.search = search;
        Agreement a = compare(
            **renderer, settings_,
            per_pixel(**renderer,
                      [&](const SurfacePoint& p) { return shade_lightcuts(tree_, {}, p, cut); }),
            true);
        EXPECT_GE(a.agree, a.geometry * 98 / 100) << bound_search_name(search);
        EXPECT_GT(a.shadowed, a.geometry / 10);
    }
}

TEST_F(Shadows, WalkSearchFinishesWhereOneInvocationWouldHitTheLoopLimit) {
    // A fine error ratio over a few thousand lights: each pixel's search
    // takes several passes of hundreds of cut nodes, each node a shadow ray
    // through the furniture's BVH. Together those passes exceed llvmpipe's
    // 65,535 loop iterations per invocation (before passes were resumed, 135
    // of these 576 pixels stopped early); each pass alone fits, and a pass the
    // limit cuts short runs again in the next dispatch, so every pixel
    // finishes and matches the CPU.
    scene_.lights = furnished_room_lights(4000, 17);
    tree_ = test::walk_tree(test::agglomerative_tree(scene_.lights));
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene_, &tree_);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.width = settings_.height = 24;
    settings_.mode = RenderMode::kLightcuts;
    settings_.criterion = CutCriterion::kBound;
    settings_.error_ratio = 0.002f;
    settings_.max_cut = 1000;
    settings_.bound_search = BoundSearch::kWalk;
    CutSettings cut;
    cut.criterion = CutCriterion::kBound;
    cut.error_ratio = settings_.error_ratio;
    cut.max_cut = settings_.max_cut;
    cut.search = BoundSearch::kWalk;
    Agreement a = compare(
        **renderer, settings_,
        per_pixel(**renderer,
                  [&](const SurfacePoint& p) { return shade_lightcuts(tree_, {}, p, cut); }),
        true);
    EXPECT_GE(a.agree, a.geometry * 98 / 100);
    EXPECT_GT(a.shadow_rays, uint64_t(a.geometry) * 1000) << "the passes should trace many rays";
}

TEST_F(Shadows, RadiusCriterionAndClassicLightsMatchTheCpu) {
    // Ranged lights so the radius criterion has finite radii, and two classic
    // lights that are shaded one by one, with shadows too.
    for (SceneLight& l : scene_.lights) l.range = 4.0f;
    std::vector<SceneLight> classic;
    for (glm::vec3 at : {glm::vec3(0.0f, 0.3f, 0.1f), glm::vec3(-3.0f, 2.5f, -3.0f)}) {
        SceneLight c = scene_.lights.front();
        c.position = at;
        c.classic = true;
        c.range = 0.0f;
        test::set_unit_guid(c, 500 + uint32_t(classic.size()));
        classic.push_back(c);
    }
    tree_ = test::walk_tree(test::agglomerative_tree(scene_.lights));
    scene_.lights.insert(scene_.lights.end(), classic.begin(), classic.end());
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene_, &tree_);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kLightcuts;
    settings_.criterion = CutCriterion::kRadius;
    CutSettings radius;
    Agreement a = compare(
        **renderer, settings_,
        per_pixel(**renderer,
                  [&](const SurfacePoint& p) { return shade_lightcuts(tree_, classic, p, radius); }),
        true);
    EXPECT_GE(a.agree, a.geometry * 98 / 100);
}

TEST_F(Shadows, ReferenceOverManyDispatchesMatchesTheCpu) {
    // A shelf of many small boxes makes a deep BVH, so that a dispatch can
    // hold only a few lights within llvmpipe's loop budget.
    for (int i = 0; i < 24; ++i)
        for (int j = 0; j < 24; ++j) {
            const float x = -3.0f + 0.25f * float(i), z = -3.0f + 0.25f * float(j);
            Mesh top = test::make_quad({x, 1.2f, z + 0.1f}, {0.1f, 0.0f, 0.0f}, {0.0f, 0.0f, -0.1f},
                                       0);
            scene_.meshes.push_back(top);
        }
    scene_.lights = furnished_room_lights(400, 12);
    tree_ = test::walk_tree(test::agglomerative_tree(scene_.lights));
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene_, &tree_);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kReference;
    const uint32_t chunk = (*renderer)->reference_chunk();
    std::printf("  %u BVH nodes, %u leaves per dispatch\n",
                uint32_t((*renderer)->shadow_bvh().gpu_nodes().size()), chunk);
    if ((*renderer)->leaf_count() <= chunk)
        GTEST_SKIP() << "this device has no loop limit: one dispatch holds every light";
    Agreement a = compare(**renderer, settings_, leaves_frame(**renderer, tree_), false);
    EXPECT_GE(a.agree, a.geometry * 99 / 100);
    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok());
    EXPECT_GT(stats->reference_dispatches, 1u);
}

TEST_F(Shadows, ReferenceOverSeveralSubmissionsIsTheSameFrame) {
    // A budget of one light evaluation puts every dispatch in a submission of
    // its own (the leaves, then the parts' sum of this small image, whose
    // four workgroups split the leaves in layers): the same bytes and counts
    // as one submission.
    Result<std::unique_ptr<Renderer>> whole = client::Renderer::create(*context_, scene_, &tree_);
    ASSERT_TRUE(whole.ok()) << whole.error();
    RendererOptions split_options;
    split_options.reference_evaluations_per_submission = 1;
    Result<std::unique_ptr<Renderer>> split =
        client::Renderer::create(*context_, scene_, &tree_, split_options);
    ASSERT_TRUE(split.ok()) << split.error();
    settings_.mode = RenderMode::kReference;
    settings_.width = settings_.height = 16;
    Result<RenderStats> one = (*whole)->render(settings_);
    Result<RenderStats> several = (*split)->render(settings_);
    ASSERT_TRUE(one.ok() && several.ok());
    EXPECT_EQ(one->timing.submissions, 1u);
    EXPECT_GT(several->timing.submissions, 1u);
    EXPECT_EQ((*whole)->read_hdr().value(), (*split)->read_hdr().value());
    EXPECT_EQ(one->shadows.rays, several->shadows.rays);
    EXPECT_GT(several->shadows.rays, 0u);
    EXPECT_EQ(one->geometry_pixels, several->geometry_pixels);
    EXPECT_EQ(several->nonfinite_pixels, 0u);
    EXPECT_GT(several->timing.render_ms, 0.0);
}

TEST_F(Shadows, RaysThatVisitEveryNodeStayWithinTheLoopBudget) {
    // Worst case for the dispatch split: a stack of triangles whose boxes
    // every near-vertical ray enters but whose triangles it misses (each
    // covers the half of its square away from the axis), so each ray visits
    // every node and tests every triangle. A regression test: a triangle loop
    // the compiler did not unroll once spent 9x the budget counted per ray.
    Scene scene;
    scene.materials = make_room_scene().materials;
    scene.meshes.push_back(make_room_scene().meshes[0]);  // the floor
    Mesh stack;
    for (int k = 0; k < 600; ++k) {
        const float y = 0.5f + 0.003f * float(k);
        const uint32_t base = uint32_t(stack.positions.size());
        stack.positions.insert(stack.positions.end(),
                               {{-0.9f, y, 1.0f}, {1.0f, y, 1.0f}, {1.0f, y, -0.9f}});
        stack.normals.insert(stack.normals.end(), 3, glm::vec3(0, 1, 0));
        stack.indices.insert(stack.indices.end(), {base, base + 1, base + 2});
    }
    stack.material = 0;
    scene.meshes.push_back(stack);
    std::vector<SceneLight> lights = furnished_room_lights(1200, 13);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> jitter(-0.01f, 0.01f);
    for (SceneLight& l : lights) l.position = {jitter(rng), 2.8f + jitter(rng), jitter(rng)};
    scene.lights = lights;
    scene.bounds_min = {-5, 0, -5};
    scene.bounds_max = {5, 3, 5};
    WalkTree tree = test::walk_tree(test::agglomerative_tree(lights));
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    ASSERT_TRUE((*renderer)->effects().shadows);
    if ((*renderer)->leaf_count() <= (*renderer)->reference_chunk())
        GTEST_SKIP() << "this device has no loop limit: one dispatch holds every light";
    RenderSettings settings;
    settings.mode = RenderMode::kReference;
    settings.width = settings.height = 16;
    settings.camera.eye = {-0.6f, 0.3f, -0.6f};
    settings.camera.target = {0.0f, 0.0f, 0.0f};
    settings.camera.yfov = 0.5f;
    Agreement a = compare(**renderer, settings, leaves_frame(**renderer, tree), false);
    EXPECT_GE(a.agree, a.geometry * 99 / 100);
    EXPECT_GT(a.geometry, 0u);
}

TEST_F(Shadows, HardCasesStayFiniteAndMatchTheCpu) {
    // A light lying on the table top, one on the floor where the camera
    // looks, a spot inside a pillar, a sun the closed room hides entirely,
    // and a light 1e12 times brighter than the rest: finite everywhere, the
    // same answer as the CPU.
    std::vector<SceneLight> lights = furnished_room_lights(30, 21);
    SceneLight on_table = lights.front();
    on_table.position = {0.0f, 0.78f, 0.0f};
    SceneLight on_floor = lights.front();
    on_floor.position = {0.0f, 0.0f, 2.0f};
    SceneLight in_pillar = lights.front();
    in_pillar.type = LightType::kSpot;
    in_pillar.position = {-3.0f, 1.5f, -2.0f};
    in_pillar.direction = {0.0f, -1.0f, 0.0f};
    in_pillar.outer_cone_angle = 0.6f;
    in_pillar.inner_cone_angle = 0.3f;
    SceneLight sun = lights.front();
    sun.type = LightType::kDirectional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    SceneLight blinding = lights.front();
    blinding.position = {4.0f, 2.5f, 4.0f};
    blinding.intensity = lights.front().intensity * 1e12f;
    uint32_t id = 800;
    for (SceneLight* l : {&on_table, &on_floor, &in_pillar, &sun, &blinding}) {
        test::set_unit_guid(*l, id++);
        lights.push_back(*l);
    }
    scene_.lights = lights;
    tree_ = test::walk_tree(test::agglomerative_tree(lights));
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene_, &tree_);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    ASSERT_TRUE((*renderer)->effects().shadows);
    settings_.mode = RenderMode::kReference;
    Agreement a = compare(**renderer, settings_, leaves_frame(**renderer, tree_), false);
    EXPECT_GE(a.agree, a.geometry * 99 / 100);
    settings_.mode = RenderMode::kLightcuts;
    settings_.criterion = CutCriterion::kBound;
    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_EQ(stats->nonfinite_pixels, 0u);
    EXPECT_GT(stats->shadows.rays, 0u);
}

TEST_F(Shadows, SkippedInAnEmptyRoomAndWhenTurnedOff) {
    Scene empty = make_room_scene();
    empty.lights = scene_.lights;
    WalkTree tree = test::walk_tree(test::agglomerative_tree(empty.lights));
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, empty, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    EXPECT_FALSE((*renderer)->effects().shadows);
    settings_.mode = RenderMode::kReference;
    Result<RenderStats> stats = (*renderer)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_FALSE(stats->shadows.simulated);
    EXPECT_EQ(stats->shadows.rays, 0u);

    RendererOptions off;
    off.shadows = ShadowMode::kOff;
    Result<std::unique_ptr<Renderer>> no_shadows = client::Renderer::create(*context_, scene_, &tree_, off);
    ASSERT_TRUE(no_shadows.ok()) << no_shadows.error();
    EXPECT_FALSE((*no_shadows)->effects().shadows);
    stats = (*no_shadows)->render(settings_);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_EQ(stats->shadows.rays, 0u);
}

TEST_F(Shadows, ALightInsideAClosedBoxLightsNothingOutside) {
    // Hard case: every ray to a light sealed in the cabinet is blocked; the
    // image is finite and no brighter than without that light.
    SceneLight sealed = scene_.lights.front();
    sealed.position = {3.5f, 0.7f, -4.6f};  // inside the cabinet
    sealed.intensity = 1e6f;
    test::set_unit_guid(sealed, 777);
    std::vector<SceneLight> with = scene_.lights;
    with.push_back(sealed);
    WalkTree tree = test::walk_tree(test::agglomerative_tree(with));
    Scene scene = scene_;
    scene.lights = with;
    Result<std::unique_ptr<Renderer>> renderer = client::Renderer::create(*context_, scene, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    settings_.mode = RenderMode::kReference;
    Agreement a = compare(**renderer, settings_, leaves_frame(**renderer, tree), false);
    EXPECT_GE(a.agree, a.geometry * 99 / 100);
}

}  // namespace
}  // namespace lc::client
