// The real-time mode (RenderMode::kRealtime, RealtimePass): stochastic
// lightcuts with at most K shadow rays per pixel and frame, accumulated over
// frames. On the furnished room with shadows: the ray budget holds; the
// accumulated image converges to the reference as 1 / frames with
// independent frames (the estimator is unbiased), sooner with the default
// spread ones, and without a floor; a still view changes from frame to frame no more than its
// noise predicts; a moved camera keeps its reprojected history; the same
// frames give the same bytes; validation stays silent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "editor_client/render/renderer.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

constexpr uint32_t kSize = 48;

// Sum over lit pixels of the squared error over the sum of the squared
// reference: the relative mean squared error.
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

// Mean over lit pixels and channels of |a - b|, over the mean of `scale`.
double relative_mean_difference(const std::vector<float>& a, const std::vector<float>& b,
                                const std::vector<float>& scale) {
    double difference = 0.0, total = 0.0;
    for (size_t i = 0; i + 3 < a.size(); i += 4) {
        if (scale[i + 3] == 0.0f) continue;
        for (size_t c = 0; c < 3; ++c) {
            difference += std::abs(double(a[i + c]) - double(b[i + c]));
            total += double(scale[i + c]);
        }
    }
    return total > 0.0 ? difference / total : 0.0;
}

class Realtime : public test::VulkanTest {
protected:
    void SetUp() override {
        VulkanTest::SetUp();
        if (!context_) return;
        scene_ = make_furnished_room_scene();
        scene_.lights = test::room_lights(1500, 23, LightTypeChoice::kPoint, 0.8f);
        tree_ = test::agglomerative_tree(scene_.lights);
        renderer_ = make_renderer(0);
        settings_.width = settings_.height = kSize;
        settings_.camera = test::furnished_room_camera();
        settings_.mode = RenderMode::kReference;
        reference_ = render(*renderer_, settings_);
        settings_.mode = RenderMode::kRealtime;
        settings_.realtime_cut = 8;
        settings_.realtime_rays = 0;
    }
    // filter_frames 0: the image is the plain running mean from the first frame.
    std::unique_ptr<Renderer> make_renderer(uint32_t filter_frames, bool spread_frames = true) {
        RendererOptions options;
        options.realtime.filter_frames = filter_frames;
        options.realtime.spread_frames = spread_frames;
        Result<std::unique_ptr<Renderer>> renderer =
            test::create_renderer(*context_, scene_, &tree_, options);
        EXPECT_TRUE(renderer.ok()) << renderer.error();
        if (renderer.ok()) {
            EXPECT_TRUE((*renderer)->effects().shadows);
        }
        return renderer.ok() ? std::move(renderer).value() : nullptr;
    }
    std::vector<double> errors_after(const RenderSettings& settings, std::vector<uint32_t> counts,
                                     bool spread);
    std::vector<float> render(Renderer& renderer, const RenderSettings& settings) {
        Result<RenderStats> stats = renderer.render(settings);
        EXPECT_TRUE(stats.ok()) << stats.error();
        if (!stats.ok()) return {};
        last_stats_ = *stats;
        EXPECT_EQ(stats->nonfinite_pixels, 0u);
        return renderer.read_hdr().value();
    }
    Scene scene_;
    LightTree tree_;
    std::unique_ptr<Renderer> renderer_;
    RenderSettings settings_;
    std::vector<float> reference_;
    RenderStats last_stats_;
};

TEST_F(Realtime, TracesAtMostTheCutsNodesInShadowRaysPerPixel) {
    for (uint32_t cut : {1u, 8u, 32u}) {
        SCOPED_TRACE(testing::Message() << "cut " << cut);
        settings_.realtime_cut = cut;
        ASSERT_FALSE(render(*renderer_, settings_).empty());
        const RenderStats& s = last_stats_;
        std::printf("  cut %u: %llu shadow rays over %llu lit pixels (%.2f a pixel), avg cut %.2f\n", cut,
                    (unsigned long long)s.shadows.rays, (unsigned long long)s.geometry_pixels,
                    double(s.shadows.rays) / double(s.geometry_pixels), s.cuts.avg_cut);
        EXPECT_GT(s.geometry_pixels, kSize * kSize / 2);
        EXPECT_GT(s.shadows.rays, 0u);
        EXPECT_LE(s.shadows.rays, uint64_t(cut) * s.geometry_pixels);
        EXPECT_LE(s.cuts.max_cut, cut);
        EXPECT_EQ(s.realtime.cut, cut);
        EXPECT_EQ(s.cuts.loop_limit_stops, 0u);
        // 1,500 lights: a cut of more than one node has room to refine.
        if (cut > 1) {
            EXPECT_GT(s.cuts.avg_cut, 0.9 * cut);
        }
    }
}

TEST_F(Realtime, ShadowRayBudgetTracesAtMostItsRaysPerPixel) {
    settings_.realtime_cut = 16;
    for (uint32_t rays : {1u, 4u}) {
        SCOPED_TRACE(testing::Message() << "rays " << rays);
        settings_.realtime_rays = rays;
        ASSERT_FALSE(render(*renderer_, settings_).empty());
        const RenderStats& s = last_stats_;
        std::printf("  cut 16, budget %u: %.2f shadow rays a lit pixel\n", rays,
                    double(s.shadows.rays) / double(s.geometry_pixels));
        EXPECT_EQ(s.realtime.rays, rays);
        EXPECT_GT(s.shadows.rays, uint64_t(rays) * s.geometry_pixels / 2);
        EXPECT_LE(s.shadows.rays, uint64_t(rays) * s.geometry_pixels);
    }
}

// A budget of at least the cut traces one ray per cut node, as no budget does.
TEST_F(Realtime, BudgetAsLargeAsTheCutChangesNothing) {
    std::unique_ptr<Renderer> unbudgeted = make_renderer(16);
    std::unique_ptr<Renderer> budgeted = make_renderer(16);
    ASSERT_TRUE(unbudgeted && budgeted);
    RenderSettings wide = settings_;
    wide.realtime_rays = settings_.realtime_cut;
    settings_.realtime_rays = 0;
    std::vector<float> a, b;
    for (int f = 0; f < 2; ++f) {
        a = render(*unbudgeted, settings_);
        b = render(*budgeted, wide);
    }
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(a, b);
}

// The mean relative error of `settings`' accumulated image after each of
// `counts` frames of a fresh history, its frames spread along their sequences
// or drawn independently. The mean error, not the MSE: a few rare large
// estimates (a light drawn with a small probability) decide the MSE of a
// 48x48 image, and whether one lands in frames 17 to 64 or later is chance.
std::vector<double> Realtime::errors_after(const RenderSettings& settings, std::vector<uint32_t> counts,
                                           bool spread) {
    std::unique_ptr<Renderer> plain = make_renderer(0, spread);
    EXPECT_TRUE(plain);
    std::vector<double> errors;
    uint32_t frames = 0;
    for (uint32_t target : counts) {
        std::vector<float> image;
        for (; plain && frames < target; ++frames) image = render(*plain, settings);
        EXPECT_FALSE(image.empty());
        if (image.empty()) return {};
        EXPECT_EQ(plain->realtime_frames(), target);
        errors.push_back(relative_mean_difference(image, reference_, reference_));
        std::printf("  %u rays (0: a ray per node), %s frames, %3u of them: mean error %.4f, relative MSE %.3g\n",
                    settings.realtime_rays, spread ? "spread" : "independent", target, errors.back(),
                    relative_mse(image, reference_));
    }
    return errors;
}

// Independent frames: each 4x more frames halve the mean error (an unbiased
// estimate's deviation falls as 1 / sqrt(frames), its variance as 1 / frames),
// within 1.6x to 3x; a bias would make it level off.
void expect_one_over_frames(const std::vector<double>& errors) {
    ASSERT_EQ(errors.size(), 3u);
    for (size_t i = 1; i < errors.size(); ++i) {
        EXPECT_LT(errors[i], errors[i - 1] / 1.6) << i;
        EXPECT_GT(errors[i], errors[i - 1] / 3.0) << i;
    }
}

// Spread frames: each 4x more frames divide the mean error by 1.6 at least, up
// to 256 frames, where a per-pixel bias (a pixel's sequences in step with each
// other, converging to a wrong answer) would have levelled it off.
void expect_no_floor(const std::vector<double>& errors) {
    ASSERT_EQ(errors.size(), 4u);
    for (size_t i = 1; i < errors.size(); ++i) EXPECT_LT(errors[i], errors[i - 1] / 1.6) << i;
}

// The picks are unbiased: their accumulated image converges to the reference
// as 1 / frames, like the full cut's.
TEST_F(Realtime, BudgetedImageConvergesToTheReference) {
    settings_.realtime_rays = 1;
    expect_one_over_frames(errors_after(settings_, {4, 16, 64}, false));
}

TEST_F(Realtime, AccumulatedImageConvergesToTheReferenceAsOneOverFrames) {
    expect_one_over_frames(errors_after(settings_, {4, 16, 64}, false));
}

// The default: frames spread their draws evenly, so 64 of them come closer to
// the reference than 64 independent ones, and the mean still converges to it
// (with a budget too: the picks' sequence is apart from the draws').
TEST_F(Realtime, SpreadFramesConvergeSoonerWithoutBias) {
    const std::vector<double> spread = errors_after(settings_, {4, 16, 64, 256}, true);
    const std::vector<double> independent = errors_after(settings_, {64}, false);
    ASSERT_EQ(spread.size(), 4u);
    ASSERT_EQ(independent.size(), 1u);
    EXPECT_LT(spread[2], 0.8 * independent[0]);
    expect_no_floor(spread);
    settings_.realtime_rays = 1;
    expect_no_floor(errors_after(settings_, {4, 16, 64, 256}, true));
}

TEST_F(Realtime, StillViewChangesNoMoreThanItsNoisePredicts) {
    std::unique_ptr<Renderer> plain = make_renderer(0);
    ASSERT_TRUE(plain);
    const std::vector<float> first = render(*plain, settings_);
    // One frame's noise: how far a single estimate is from the answer.
    const double noise = relative_mean_difference(first, reference_, reference_);
    std::vector<float> previous = first;
    for (uint32_t n = 2; n <= 32; ++n) {
        const std::vector<float> image = render(*plain, settings_);
        ASSERT_FALSE(image.empty());
        // The running mean moves by (estimate - mean) / n.
        const double change = relative_mean_difference(image, previous, reference_);
        if (n == 2 || n == 8 || n == 32)
            std::printf("  frame %2u: change %.4f, one frame's noise / n %.4f\n", n, change, noise / n);
        EXPECT_LT(change, 2.0 * noise / n) << "frame " << n;
        previous = image;
    }
}

TEST_F(Realtime, MovedCameraKeepsItsReprojectedHistory) {
    std::unique_ptr<Renderer> plain = make_renderer(0);
    ASSERT_TRUE(plain);
    for (int f = 0; f < 32; ++f) ASSERT_FALSE(render(*plain, settings_).empty());
    RenderSettings moved = settings_;
    moved.camera.eye += glm::vec3(0.05f, 0.0f, 0.0f);
    moved.mode = RenderMode::kReference;
    const std::vector<float> moved_reference = render(*renderer_, moved);
    moved.mode = RenderMode::kRealtime;
    const std::vector<float> with_history = render(*plain, moved);
    EXPECT_EQ(plain->realtime_frames(), 1u) << "a moved view counts its frames anew";
    std::unique_ptr<Renderer> fresh = make_renderer(0);
    ASSERT_TRUE(fresh);
    const std::vector<float> without_history = render(*fresh, moved);
    const double kept = relative_mse(with_history, moved_reference);
    const double alone = relative_mse(without_history, moved_reference);
    std::printf("  moved camera: relative MSE %.3g with history, %.3g without\n", kept, alone);
    EXPECT_LT(kept, 0.5 * alone);
}

TEST_F(Realtime, ANewSettingStartsANewHistory) {
    ASSERT_FALSE(render(*renderer_, settings_).empty());
    ASSERT_FALSE(render(*renderer_, settings_).empty());
    EXPECT_EQ(renderer_->realtime_frames(), 2u);
    EXPECT_EQ(last_stats_.realtime.frames, 2u);
    settings_.exposure *= 2.0f;  // tone mapping only: the history stays
    ASSERT_FALSE(render(*renderer_, settings_).empty());
    EXPECT_EQ(renderer_->realtime_frames(), 3u);
    settings_.realtime_cut = 16;
    ASSERT_FALSE(render(*renderer_, settings_).empty());
    EXPECT_EQ(renderer_->realtime_frames(), 1u);
    ASSERT_TRUE(test::set_tree(*renderer_, &tree_).ok());
    ASSERT_FALSE(render(*renderer_, settings_).empty());
    EXPECT_EQ(renderer_->realtime_frames(), 1u);
}

TEST_F(Realtime, SameFramesGiveTheSameBytes) {
    std::vector<float> a, b;
    std::unique_ptr<Renderer> first = make_renderer(16);
    std::unique_ptr<Renderer> second = make_renderer(16);
    ASSERT_TRUE(first && second);
    for (int f = 0; f < 3; ++f) {
        a = render(*first, settings_);
        b = render(*second, settings_);
    }
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(a, b);
    // And the frames differ: the draws change every frame.
    const std::vector<float> next = render(*first, settings_);
    EXPECT_NE(next, a);
}

}  // namespace
}  // namespace lc::client
