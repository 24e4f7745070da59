// `render --mode realtime --sweep-realtime`: the real-time modes side by side
// on one scene, each variant's still frames accumulated and its frames along
// an orbit measured against references (editor_client/render/sweeps/).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "editor_client/render/renderer.h"
#include "editor_client/render/sweeps/camera_path.h"
#include "editor_client/render/sweeps/equal_budget.h"
#include "editor_client/render/sweeps/realtime_sweep.h"
#include "editor_client/render/sweeps/realtime_variant.h"
#include "editor_client/scene/scene_generator.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

TEST(CountList, ParsesAscendingCountsAndNamesTheBadOne) {
    Result<std::vector<uint32_t>> ok = parse_count_list("1,4,16", "--sweep-frames", 1, 64);
    ASSERT_TRUE(ok.ok()) << ok.error();
    EXPECT_EQ(*ok, (std::vector<uint32_t>{1, 4, 16}));
    for (const char* bad : {"", "4,", "0", "65", "8,4", "4,4", "a", "1;2", "-1"}) {
        Result<std::vector<uint32_t>> r = parse_count_list(bad, "--sweep-frames", 1, 64);
        EXPECT_FALSE(r.ok()) << bad;
        if (!r.ok()) {
            EXPECT_NE(r.error().find("--sweep-frames"), std::string::npos) << r.error();
        }
    }
}

TEST(RealtimeVariants, ParsesEachKindAndTheOlderCutList) {
    RenderSettings base;
    base.error_ratio = 0.02f;
    base.realtime_rays = 0;
    Result<std::vector<RealtimeVariant>> ok = parse_realtime_variants("lc,K8r1,16,lc0.05,K4r8", base);
    ASSERT_TRUE(ok.ok()) << ok.error();
    ASSERT_EQ(ok->size(), 5u);
    const char* labels[] = {"lc0.02", "K8r1", "K16", "lc0.05", "K4"};  // 8 rays over a cut of 4: one a node
    for (size_t i = 0; i < 5; ++i) EXPECT_EQ((*ok)[i].label, labels[i]);
    const RenderSettings lc = variant_settings((*ok)[3], base);
    EXPECT_EQ(lc.mode, RenderMode::kLightcuts);
    EXPECT_FLOAT_EQ(lc.error_ratio, 0.05f);
    EXPECT_FALSE((*ok)[3].accumulates);
    const RenderSettings k8 = variant_settings((*ok)[1], base);
    EXPECT_EQ(k8.mode, RenderMode::kRealtime);
    EXPECT_EQ(k8.realtime_cut, 8u);
    EXPECT_EQ(k8.realtime_rays, 1u);
    EXPECT_TRUE((*ok)[1].accumulates);
    EXPECT_EQ(variant_settings((*ok)[2], base).realtime_rays, 0u) << "a bare cut size keeps --realtime-rays";
}

TEST(RealtimeVariants, ReadsReSTIRWithItsCandidates) {
    RenderSettings base;
    base.restir.candidates = 8;
    Result<std::vector<RealtimeVariant>> ok = parse_realtime_variants("restir,restir32,K8r1", base);
    ASSERT_TRUE(ok.ok()) << ok.error();
    ASSERT_EQ(ok->size(), 3u);
    EXPECT_EQ((*ok)[0].label, "restir");
    EXPECT_EQ((*ok)[1].label, "restir32");
    const RenderSettings m32 = variant_settings((*ok)[1], base);
    EXPECT_EQ(m32.mode, RenderMode::kRestir);
    EXPECT_EQ(m32.restir.candidates, 32u);
    EXPECT_EQ(variant_settings((*ok)[0], base).restir.candidates, 8u);
    EXPECT_TRUE((*ok)[0].accumulates);
    EXPECT_FALSE(parse_realtime_variants("restir0", base).ok());
    EXPECT_FALSE(parse_realtime_variants("restir65", base).ok());
}

TEST(RealtimeVariants, NamesTheBadItem) {
    const RenderSettings base;
    for (const char* bad : {"", "K", "K0", "K33", "K8r0", "K8r", "x", "lc-1", "lcx", "16,K16", "8,,16", "restirx", "restir,restir"}) {
        Result<std::vector<RealtimeVariant>> r = parse_realtime_variants(bad, base);
        EXPECT_FALSE(r.ok()) << bad;
        if (!r.ok()) {
            EXPECT_NE(r.error().find("--sweep-realtime"), std::string::npos) << r.error();
        }
    }
}

TEST(EqualBudget, InterpolatesInLogLogBetweenTheMeasuredPoints) {
    // Error falling as 1 / frames, a frame costing 2 ms.
    const std::vector<CostErrorPoint> points = {{2.0, 1.0}, {8.0, 0.25}, {32.0, 0.0625}};
    EXPECT_DOUBLE_EQ(error_at_budget(points, 2.0), 1.0);
    EXPECT_DOUBLE_EQ(error_at_budget(points, 32.0), 0.0625);
    EXPECT_NEAR(error_at_budget(points, 4.0), 0.5, 1e-12) << "on the power law between its points";
    EXPECT_NEAR(error_at_budget(points, 16.0), 0.125, 1e-12);
    EXPECT_TRUE(std::isnan(error_at_budget(points, 1.0))) << "not even the first frame count";
    EXPECT_TRUE(std::isnan(error_at_budget(points, 64.0))) << "past the last: no guess";
    EXPECT_TRUE(std::isnan(error_at_budget({}, 1.0)));
    // An error of 0 falls back to linear interpolation.
    const std::vector<CostErrorPoint> exact = {{1.0, 0.5}, {3.0, 0.0}};
    EXPECT_DOUBLE_EQ(error_at_budget(exact, 2.0), 0.25);
}

TEST(OrbitPath, TurnsAboutTheTargetEvenly) {
    RenderCamera start;
    start.eye = {0.0f, 1.0f, 4.0f};
    start.target = {0.0f, 1.0f, 0.0f};
    const std::vector<RenderCamera> path = orbit_path(start, 5, 90.0f);
    ASSERT_EQ(path.size(), 5u);
    EXPECT_EQ(path.front(), start);
    for (const RenderCamera& c : path) {
        EXPECT_NEAR(glm::length(c.eye - c.target), 4.0f, 1e-5f);
        EXPECT_EQ(c.target, start.target);
        EXPECT_FLOAT_EQ(c.eye.y, 1.0f) << "about the up axis";
    }
    EXPECT_NEAR(path.back().eye.x, 4.0f, 1e-5f) << "a quarter turn about +Y takes +Z to +X";
    EXPECT_NEAR(path.back().eye.z, 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(path[1].eye, path[0].eye), glm::distance(path[4].eye, path[3].eye), 1e-5f);
    EXPECT_EQ(orbit_path(start, 0).size(), 0u);
}

using RealtimeSweepRender = test::VulkanTest;

// Rows of one variant on one camera kind, in order.
std::vector<RealtimeSweepRow> rows_of(const RealtimeSweep& sweep, const std::string& label, bool moving) {
    std::vector<RealtimeSweepRow> rows;
    for (const RealtimeSweepRow& r : sweep.rows) {
        if (r.label == label && r.moving == moving) rows.push_back(r);
    }
    return rows;
}

TEST_F(RealtimeSweepRender, VariantsSideBySideStillAndMoving) {
    Scene scene = make_furnished_room_scene();
    scene.lights = test::room_lights(1500, 5, LightTypeChoice::kPoint, 0.8f);
    const LightTree tree = test::agglomerative_tree(scene.lights);
    RendererOptions options;
    options.realtime.filter_frames = 0;  // the plain mean, as the command's sweep renders it
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene, &tree, options);
    ASSERT_TRUE(renderer.ok()) << renderer.error();
    RenderSettings settings;
    settings.width = settings.height = 40;
    settings.camera = test::furnished_room_camera();
    settings.realtime_rays = 2;
    RealtimeSweepPlan plan;
    plan.variants = *parse_realtime_variants("lc0.2,4,8", settings);  // a coarse, cheap lightcut
    plan.frame_counts = {2, 8, 32};
    plan.path_frames = 4;
    Result<RealtimeSweep> sweep = run_realtime_sweep(**renderer, settings, plan);
    ASSERT_TRUE(sweep.ok()) << sweep.error();
    print_realtime_sweep(stdout, *sweep);
    ASSERT_EQ(sweep->rows.size(), 3u * (3u + 4u));
    EXPECT_GT(sweep->reference_ms, 0.0);
    RenderSettings next = settings;
    next.mode = RenderMode::kRealtime;
    next.realtime_cut = 8;  // the sweep's last
    ASSERT_TRUE((*renderer)->render(next).ok());
    EXPECT_EQ((*renderer)->realtime_frames(), 1u) << "the sweep's history is not the caller's";

    const std::vector<RealtimeSweepRow> lc = rows_of(*sweep, "lc0.2", false);
    ASSERT_EQ(lc.size(), 3u);
    EXPECT_EQ(lc[0].rel_mse, lc[2].rel_mse) << "deterministic: one image at every count";
    EXPECT_NEAR(lc[2].total_ms, 16.0 * lc[0].total_ms, 1e-6 * lc[2].total_ms);
    for (const char* label : {"K4r2", "K8r2"}) {  // the base budget of 2 in the label
        const std::vector<RealtimeSweepRow> still = rows_of(*sweep, label, false);
        ASSERT_EQ(still.size(), 3u);
        for (const RealtimeSweepRow& r : still) {
            EXPECT_LE(r.shadow_rays_per_pixel, 2.0) << "at most the budget's rays a lit pixel";
            EXPECT_GT(r.shadow_rays_per_pixel, 1.0);
        }
        // 16x the frames: the unbiased mean's squared error falls about 16x.
        EXPECT_LT(still[2].rel_mse, still[0].rel_mse / 4.0) << label;
        const std::vector<RealtimeSweepRow> moving = rows_of(*sweep, label, true);
        ASSERT_EQ(moving.size(), 4u);
        for (size_t i = 0; i < moving.size(); ++i) {
            EXPECT_EQ(moving[i].frames, i + 1);
            EXPECT_TRUE(std::isfinite(moving[i].rel_mse) && moving[i].rel_mse > 0.0) << label << " frame " << i;
            EXPECT_GT(moving[i].frame_ms, 0.0);
        }
    }
    ASSERT_EQ(sweep->summaries.size(), 3u);
    const RealtimeSweepRow& cheapest = *std::find_if(sweep->rows.begin(), sweep->rows.end(), [&](const auto& r) {
        return r.label == sweep->baseline && !r.moving && r.frames == 32;
    });
    EXPECT_DOUBLE_EQ(sweep->budget_ms, cheapest.total_ms);
    for (const RealtimeSweepSummary& s : sweep->summaries) {
        EXPECT_TRUE(std::isfinite(s.path_rel_mse)) << s.label;
        if (s.label == sweep->baseline) {
            EXPECT_DOUBLE_EQ(s.equal_time_rel_mse, cheapest.rel_mse) << "its own budget: its last point";
            EXPECT_DOUBLE_EQ(s.path_equal_time_rel_mse, s.path_rel_mse);
        }
    }

    const std::filesystem::path csv = std::filesystem::temp_directory_path() / "lc_realtime_sweep_test.csv";
    ASSERT_TRUE(write_realtime_sweep_csv(csv, *sweep).ok());
    ASSERT_TRUE(write_realtime_summary_csv(realtime_summary_path(csv), *sweep).ok());
    auto count_lines = [](const std::filesystem::path& path) {
        std::ifstream in(path);
        std::string line;
        int lines = 0;
        while (std::getline(in, line)) ++lines;
        return lines;
    };
    EXPECT_EQ(count_lines(csv), 22) << "a header and a row per variant and frame";
    EXPECT_EQ(realtime_summary_path(csv).filename(), "lc_realtime_sweep_test_equal.csv");
    EXPECT_EQ(count_lines(realtime_summary_path(csv)), 4) << "a header and a row per variant";
    std::filesystem::remove(csv);
    std::filesystem::remove(realtime_summary_path(csv));
}

}  // namespace
}  // namespace lc::client
