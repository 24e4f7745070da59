// llvmpipe stops an invocation's loops after 65,535 iterations in total, without
// a word. Above that many lights (or tree nodes) the renderer must still sum every
// light, or refuse; it must never return a silently truncated sum.
#include <gtest/gtest.h>

#include <random>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "editor_client/render/renderer.h"
#include "render_test_support.h"

namespace lc {
namespace {

using client::RenderMode;
using client::Renderer;
using client::RenderSettings;

// The floor with `count` unbounded dim point lights scattered above it.
lc::Scene floor_with_scattered_lights(uint32_t count, uint32_t seed) {
    lc::Scene scene = test::make_floor_scene();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> xz(-4.5f, 4.5f), y(0.5f, 4.5f);
    for (uint32_t i = 0; i < count; ++i) {
        SceneLight light = test::point_light({xz(rng), y(rng), xz(rng)}, glm::vec3(1.0f), 0.01f);
        test::set_unit_guid(light, i);
        scene.lights.push_back(light);
    }
    return scene;
}

TEST(LoopLimit, ReferenceAndRadiusWalkSumEveryOneOf70000Lights) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    lc::Scene scene = floor_with_scattered_lights(70000, 3);
    // All lights unbounded: the radius criterion refines to every leaf, so its
    // cut is the whole tree and its sum is the reference.
    LightTree tree = test::make_pairing_tree(scene.lights);
    auto renderer = test::create_renderer(*context, scene, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();

    RenderSettings settings;
    settings.width = settings.height = 8;
    settings.camera = test::floor_camera();
    settings.exposure = 1.0f;
    settings.mode = RenderMode::kReference;
    ASSERT_TRUE((*renderer)->render(settings).ok());
    auto reference = (*renderer)->read_hdr();
    ASSERT_TRUE(reference.ok());
    auto gbuffer = (*renderer)->read_gbuffer();
    ASSERT_TRUE(gbuffer.ok()) << gbuffer.error();

    settings.mode = RenderMode::kLightcuts;
    settings.criterion = lc::CutCriterion::kRadius;
    auto stats = (*renderer)->render(settings);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_EQ(stats->cuts.max_cut, 70000u);
    auto walked = (*renderer)->read_hdr();
    ASSERT_TRUE(walked.ok());

    // The CPU sum at one floor pixel agrees with both.
    size_t checked = 0;
    for (size_t px = 0; px < 64; ++px) {
        const auto& g = *gbuffer;
        if (g.position[4 * px + 3] == 0.0f) continue;
        const lc::SurfacePoint p = test::gbuffer_point(g, px);
        double exact = lc::shade_reference(scene.lights, p).x;
        EXPECT_NEAR((*reference)[4 * px], exact, 1e-3 * exact) << "pixel " << px;
        EXPECT_NEAR((*walked)[4 * px], exact, 1e-3 * exact) << "pixel " << px;
        ++checked;
    }
    EXPECT_GT(checked, 10u);
    EXPECT_EQ(context->validation_message_count(), 0u);
}

TEST(LoopLimit, OverBudgetWorkIsRefusedWithTheReason) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    if (!context->physical().quirks.has_loop_limit())
        GTEST_SKIP() << "the loop limit is llvmpipe's; this device has none";
    lc::Scene scene = test::make_floor_scene();
    for (uint32_t i = 0; i < 8; ++i) {
        SceneLight light = test::point_light({float(i) - 4.0f, 2.0f, 0.0f}, glm::vec3(1.0f), 1.0f);
        test::set_unit_guid(light, i);
        scene.lights.push_back(light);
    }
    LightTree tree = test::make_pairing_tree(scene.lights);
    auto renderer = test::create_renderer(*context, scene, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    RenderSettings settings;
    settings.width = settings.height = 8;
    settings.camera = test::floor_camera();
    settings.mode = RenderMode::kLightcuts;
    settings.criterion = lc::CutCriterion::kBound;
    settings.bound_search = lc::BoundSearch::kHeap;
    settings.max_cut = 4096;
    auto stats = (*renderer)->render(settings);
    ASSERT_FALSE(stats.ok());
    EXPECT_NE(stats.error().find("65535"), std::string::npos) << stats.error();
}

TEST(LoopLimit, WalkSearchCountsAPassTheLimitCutShort) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    if (!context->physical().quirks.has_loop_limit())
        GTEST_SKIP() << "the loop limit is llvmpipe's; this device has none";
    lc::Scene scene = floor_with_scattered_lights(70000, 5);
    // Every junction flagged mixed-type: always refined, so the first pass
    // walks all 139,999 nodes, two per iteration: past the 65,535 limit.
    LightTree tree = test::make_pairing_tree(scene.lights);
    for (LightTreeNode& node : tree.nodes)
        if (!node.is_leaf()) node.flags.set(kNodeMixedTypes, true);
    auto renderer = test::create_renderer(*context, scene, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    RenderSettings settings;
    settings.width = settings.height = 8;
    settings.camera = test::floor_camera();
    settings.mode = RenderMode::kLightcuts;
    settings.criterion = lc::CutCriterion::kBound;
    auto stats = (*renderer)->render(settings);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_GT(stats->geometry_pixels, 0u);
    EXPECT_EQ(stats->cuts.loop_limit_stops, stats->geometry_pixels);
    EXPECT_EQ(stats->nonfinite_pixels, 0u);
    // A normal tree of the same lights walks to the end.
    LightTree normal = test::make_pairing_tree(scene.lights);
    auto renderer2 = test::create_renderer(*context, scene, &normal);
    ASSERT_TRUE(renderer2.ok()) << renderer2.error();
    stats = (*renderer2)->render(settings);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_EQ(stats->cuts.loop_limit_stops, 0u);
    EXPECT_GT(stats->cuts.avg_cut, 1.0);
    EXPECT_EQ(context->validation_message_count(), 0u);
}

// A floor of `n` x `n` quads (2 n^2 triangles): a shadow BVH far above the
// loop budget for one shadow ray.
lc::Mesh tessellated_floor(int n, int material) {
    lc::Mesh mesh;
    const float step = 10.0f / float(n);
    for (int z = 0; z <= n; ++z) {
        for (int x = 0; x <= n; ++x) {
            mesh.positions.push_back({-5.0f + step * float(x), 0.001f, 5.0f - step * float(z)});
            mesh.normals.push_back({0.0f, 1.0f, 0.0f});
            mesh.uvs.push_back({float(x) / float(n), float(z) / float(n)});
        }
    }
    for (int z = 0; z < n; ++z) {
        for (int x = 0; x < n; ++x) {
            const uint32_t a = uint32_t(z * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1) + 1,
                           d = a + uint32_t(n + 1);
            mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        }
    }
    mesh.material = material;
    return mesh;
}

// Issue 14, item 4: a scene with no lights in reference mode was refused for
// the shadow-ray loop iterations of lights it does not have; it renders its
// emission (black elsewhere).
TEST(LoopLimit, ReferenceModeWithoutLightsRendersItsEmissionWhateverTheBvh) {
    std::unique_ptr<vk::Context> context;
    LC_REQUIRE_VULKAN(context);
    lc::Scene scene = test::make_floor_scene();
    scene.materials[0].emissive_factor = {0.25f, 0.5f, 1.0f};
    scene.meshes.push_back(tessellated_floor(160, 0));  // 51,200 triangles
    client::RendererOptions options;
    options.shadows = ShadowMode::kOn;
    auto renderer = test::create_renderer(*context, scene, nullptr, options);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    ASSERT_TRUE((*renderer)->effects().shadows);

    RenderSettings settings;
    settings.width = settings.height = 8;
    settings.camera = test::floor_camera();
    settings.exposure = 1.0f;
    settings.mode = RenderMode::kReference;
    auto stats = (*renderer)->render(settings);
    ASSERT_TRUE(stats.ok()) << stats.error();
    EXPECT_EQ(stats->nonfinite_pixels, 0u);
    auto hdr = (*renderer)->read_hdr();
    ASSERT_TRUE(hdr.ok()) << hdr.error();
    auto gbuffer = (*renderer)->read_gbuffer();
    ASSERT_TRUE(gbuffer.ok()) << gbuffer.error();
    size_t emitting = 0;
    for (size_t px = 0; px < 64; ++px) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR((*hdr)[4 * px + c], gbuffer->emissive[4 * px + c], 1e-5f)
                << "pixel " << px << " channel " << c;
        }
        emitting += gbuffer->emissive[4 * px + 2] > 0.0f ? 1u : 0u;
    }
    EXPECT_GT(emitting, 10u);

    // With one light the same BVH is over llvmpipe's budget: the case is real.
    if (!context->physical().quirks.has_loop_limit()) return;
    SceneLight light = test::point_light({0.0f, 2.0f, 0.0f}, glm::vec3(1.0f), 1.0f);
    test::set_unit_guid(light, 0);
    scene.lights.push_back(light);
    auto lit = test::create_renderer(*context, scene, nullptr, options);
    ASSERT_TRUE(lit.ok()) << lit.error();
    auto refused = (*lit)->render(settings);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().find("65535"), std::string::npos) << refused.error();
}

}  // namespace
}  // namespace lc
