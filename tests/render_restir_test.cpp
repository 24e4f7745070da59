// The ReSTIR DI mode (RenderMode::kRestir, RestirPass) on a flat scene (a
// floor and a back wall under 48 point lights, some of them behind the wall):
// the mean of a still view's frames approaches the reference, within 10% on
// the mean for both combinations (1/Z and 1/M weights; the tree draw's
// heavy tail spread by reuse keeps the tolerance loose for now); no
// non-finite pixel with no light, one light, a light behind the surface or on
// it; the same seed gives the same bytes; one shadow ray per lit pixel;
// validation stays silent (VulkanTest).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "editor_client/render/renderer.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

constexpr uint32_t kSize = 32;

// Sum over lit pixels of the squared error over the sum of the squared reference.
double relative_mse(const std::vector<float>& image, const std::vector<float>& reference) {
    double error = 0.0, energy = 0.0;
    for (size_t i = 0; i + 3 < image.size(); i += 4) {
        if (reference[i + 3] == 0.0f) continue;  // background
        for (size_t c = 0; c < 3; ++c) {
            const double d = double(image[i + c]) - double(reference[i + c]);
            error += d * d;
            energy += double(reference[i + c]) * double(reference[i + c]);
        }
    }
    return energy > 0.0 ? error / energy : 0.0;
}

// The mean image over the lit pixels over the reference's: a bias shows here.
double mean_ratio(const std::vector<float>& image, const std::vector<float>& reference) {
    double sum = 0.0, total = 0.0;
    for (size_t i = 0; i + 3 < image.size(); i += 4) {
        if (reference[i + 3] == 0.0f) continue;
        for (size_t c = 0; c < 3; ++c) {
            sum += double(image[i + c]);
            total += double(reference[i + c]);
        }
    }
    return total > 0.0 ? sum / total : 0.0;
}

std::vector<SceneLight> floor_lights(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    // At least 1.5 m above the floor: no light's 1 / d^2 peak dominates a pixel.
    std::uniform_real_distribution<float> x(-5.0f, 5.0f), y(1.5f, 4.0f), z(-7.0f, 4.0f), c(0.3f, 1.0f);
    std::vector<SceneLight> lights;
    for (uint32_t i = 0; i < count; ++i) {
        // z < -5: behind the wall, lighting only the floor's far side of nothing.
        lights.push_back(test::point_light({x(rng), y(rng), z(rng)}, {c(rng), c(rng), c(rng)}, 4.0f));
        test::set_unit_guid(lights.back(), i);
    }
    return lights;
}

class Restir : public test::VulkanTest {
protected:
    void SetUp() override {
        VulkanTest::SetUp();
        if (!context_) return;
        scene_ = test::make_floor_scene();
        settings_.width = settings_.height = kSize;
        settings_.camera = test::floor_camera();
        settings_.mode = RenderMode::kRestir;
    }
    void use_lights(std::vector<SceneLight> lights) {
        scene_.lights = std::move(lights);
        // No lights: an empty tree (the renderer draws from no node).
        tree_ = scene_.lights.empty() ? LightTree{} : test::agglomerative_tree(scene_.lights);
        // No spatial filter: the image is the plain running mean from the first frame.
        RendererOptions options;
        options.realtime.filter_frames = 0;
        Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene_, &tree_, options);
        ASSERT_TRUE(renderer.ok()) << renderer.error();
        renderer_ = std::move(renderer).value();
    }
    std::vector<float> render(const RenderSettings& settings) {
        Result<RenderStats> stats = renderer_->render(settings);
        EXPECT_TRUE(stats.ok()) << stats.error();
        if (!stats.ok()) return {};
        last_stats_ = *stats;
        EXPECT_EQ(stats->nonfinite_pixels, 0u);
        return renderer_->read_hdr().value();
    }
    std::vector<float> reference() {
        RenderSettings exact = settings_;
        exact.mode = RenderMode::kReference;
        return render(exact);
    }
    // The image after `frames` still frames (the running mean of the temporal pass).
    std::vector<float> accumulated(const RenderSettings& settings, uint32_t frames) {
        renderer_->restart_realtime();
        std::vector<float> image;
        for (uint32_t f = 0; f < frames; ++f) image = render(settings);
        return image;
    }
    Scene scene_;
    LightTree tree_;
    std::unique_ptr<Renderer> renderer_;
    RenderSettings settings_;
    RenderStats last_stats_;
};

TEST_F(Restir, UnbiasedMeanConvergesToTheReference) {
    use_lights(floor_lights(48, 5));
    const std::vector<float> exact = reference();
    settings_.restir.bias = RestirBias::kUnbiased;
    const double after_1 = relative_mse(accumulated(settings_, 1), exact);
    const std::vector<float> image = accumulated(settings_, 64);
    const double after_64 = relative_mse(image, exact);
    const double ratio = mean_ratio(image, exact);
    std::printf("  unbiased: relative MSE %.3g after 1 frame, %.3g after 64; mean ratio %.4f\n", after_1,
                after_64, ratio);
    // Measured (lavapipe, seed 0): 2.2 after 1 frame, 0.29 after 64, mean ratio 0.934. The
    // tree draw's pdf is heavy-tailed and reuse spreads a rare large weight to neighbours, so
    // the mean settles slowly: a loose bound, not yet the tight one issue 38 asks for.
    EXPECT_LT(after_64, 0.25 * after_1);
    EXPECT_LT(after_64, 0.5);
    EXPECT_NEAR(ratio, 1.0, 0.1);
}

// Biased reuse may darken or brighten where neighbours' lights differ; on a
// flat scene its mean stays within 10% of the reference (measured 1.066).
TEST_F(Restir, BiasedMeanStaysNearTheReference) {
    use_lights(floor_lights(48, 5));
    const std::vector<float> exact = reference();
    settings_.restir.bias = RestirBias::kBiased;
    const std::vector<float> image = accumulated(settings_, 64);
    const double ratio = mean_ratio(image, exact);
    const double error = relative_mse(image, exact);
    std::printf("  biased: relative MSE %.3g after 64 frames; mean ratio %.4f\n", error, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.1);
    EXPECT_LT(error, 1.0);  // measured 0.43
}

TEST_F(Restir, PowerCandidatesConvergeToo) {
    use_lights(floor_lights(48, 5));
    const std::vector<float> exact = reference();
    settings_.restir.bias = RestirBias::kUnbiased;
    settings_.restir.source = RestirSource::kPower;
    const std::vector<float> image = accumulated(settings_, 64);
    EXPECT_NEAR(mean_ratio(image, exact), 1.0, 0.15);  // measured 0.915
}

TEST_F(Restir, TracesOneShadowRayPerLitPixel) {
    use_lights(floor_lights(48, 5));
    ASSERT_FALSE(render(settings_).empty());
    EXPECT_GT(last_stats_.geometry_pixels, kSize * kSize / 2);
    EXPECT_GT(last_stats_.shadows.rays, 0u);
    EXPECT_LE(last_stats_.shadows.rays, last_stats_.geometry_pixels);
    EXPECT_EQ(last_stats_.cuts.loop_limit_stops, 0u);
}

// Frames are seeded by their number since the renderer was made (as the
// real-time mode's are): a fresh renderer repeats them.
TEST_F(Restir, SameSeedGivesTheSameBytes) {
    settings_.representative_seed = 7;
    use_lights(floor_lights(48, 5));
    const std::vector<float> first = accumulated(settings_, 3);
    use_lights(floor_lights(48, 5));
    const std::vector<float> second = accumulated(settings_, 3);
    EXPECT_EQ(first, second);
    use_lights(floor_lights(48, 5));
    settings_.representative_seed = 8;
    EXPECT_NE(accumulated(settings_, 3), first);
}

TEST_F(Restir, NoLightsGiveBlackFrames) {
    use_lights({});
    for (RestirBias bias : {RestirBias::kBiased, RestirBias::kUnbiased}) {
        settings_.restir.bias = bias;
        const std::vector<float> image = accumulated(settings_, 3);
        ASSERT_FALSE(image.empty());
        for (size_t i = 0; i + 3 < image.size(); i += 4) ASSERT_EQ(image[i], 0.0f) << i;
    }
}

TEST_F(Restir, OneLightMatchesTheReferenceExactly) {
    use_lights({test::point_light({0.5f, 2.0f, 0.0f}, {1.0f, 0.9f, 0.8f}, 6.0f)});
    test::set_unit_guid(scene_.lights[0], 0);
    const std::vector<float> exact = reference();
    for (RestirBias bias : {RestirBias::kBiased, RestirBias::kUnbiased}) {
        settings_.restir.bias = bias;
        // One light: every candidate is it, W = 1 / p_hat, the estimate exact.
        EXPECT_LT(relative_mse(accumulated(settings_, 2), exact), 1e-8);
    }
}

TEST_F(Restir, LightsBehindAndOnTheSurfaceStayFinite) {
    std::vector<SceneLight> lights{test::point_light({0.0f, -1.0f, 0.0f}, {1, 1, 1}, 5.0f),   // under the floor
                                   test::point_light({1.0f, 2.0f, -6.0f}, {1, 1, 1}, 5.0f),   // behind the wall
                                   test::point_light({-1.0f, 0.0f, 1.0f}, {1, 1, 1}, 5.0f),   // on the floor
                                   test::point_light({2.0f, 1.0f, -5.0f}, {1, 1, 1}, 5.0f)};  // on the wall
    for (uint32_t i = 0; i < lights.size(); ++i) test::set_unit_guid(lights[i], i);
    use_lights(lights);
    for (bool visibility : {false, true}) {
        for (RestirBias bias : {RestirBias::kBiased, RestirBias::kUnbiased}) {
            settings_.restir.bias = bias;
            settings_.restir.candidate_visibility = visibility;
            const std::vector<float> image = accumulated(settings_, 4);
            ASSERT_FALSE(image.empty());
            for (float v : image) ASSERT_TRUE(std::isfinite(v));
            EXPECT_EQ(last_stats_.nonfinite_pixels, 0u);
        }
    }
}

}  // namespace
}  // namespace lc::client
