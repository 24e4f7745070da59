// `render --sweep-error`: the price of accuracy on one scene, measured against
// one reference frame (editor_client/render/sweeps/error_sweep.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "editor_client/render/sweeps/error_sweep.h"
#include "editor_client/render/renderer.h"
#include "editor_client/scene/scene_generator.h"
#include "lightmass_server/builders/tree_builder.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

TEST(ErrorList, ParsesRatiosAndNamesTheBadOne) {
    Result<std::vector<float>> ok = parse_error_list("0.005,0.01,0.2");
    ASSERT_TRUE(ok.ok()) << ok.error();
    EXPECT_EQ(*ok, (std::vector<float>{0.005f, 0.01f, 0.2f}));
    for (const char* bad : {"", "0.01,", "0.01,abc", "-0.1", "nan", "0.01;0.02", "1e99"}) {
        Result<std::vector<float>> r = parse_error_list(bad);
        EXPECT_FALSE(r.ok()) << bad;
        if (!r.ok()) {
            EXPECT_NE(r.error().find("--sweep-error"), std::string::npos) << r.error();
        }
    }
}

using ErrorSweepRender = test::VulkanTest;

TEST_F(ErrorSweepRender, SmallerRatiosCostMoreAndErrLess) {
    Scene scene = make_room_scene();
    scene.lights = test::room_lights(1500, 3, LightTypeChoice::kPoint, 0.5f);
    ASSERT_EQ(scene.lights.size(), 1500u);
    const LightTree tree = test::agglomerative_tree(scene.lights);
    ASSERT_FALSE(tree.empty());
    Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene, &tree);
    ASSERT_TRUE(renderer.ok()) << renderer.error();

    RenderSettings settings;
    settings.mode = RenderMode::kLightcuts;
    settings.criterion = CutCriterion::kBound;
    settings.width = settings.height = 48;
    settings.camera.eye = {0.0f, 1.6f, 4.8f};
    settings.camera.target = {0.0f, 1.2f, -5.0f};
    settings.camera.yfov = 1.2f;
    const std::vector<float> ratios{0.002f, 0.01f, 0.05f, 0.2f};
    Result<ErrorSweep> sweep = run_error_sweep(**renderer, settings, ratios);
    ASSERT_TRUE(sweep.ok()) << sweep.error();
    print_error_sweep(stdout, *sweep);
    ASSERT_EQ(sweep->rows.size(), ratios.size());
    EXPECT_EQ(sweep->lights, 1500u);
    EXPECT_GT(sweep->reference_ms, 0.0);
    for (size_t i = 0; i < ratios.size(); ++i) {
        const ErrorSweepRow& row = sweep->rows[i];
        EXPECT_EQ(row.error_ratio, ratios[i]);
        EXPECT_TRUE(std::isfinite(row.rel_err_mean) && std::isfinite(row.max_err));
        EXPECT_GT(row.avg_cut, 1.0);
        EXPECT_GE(row.cut_p99, uint32_t(row.avg_cut));
        if (i == 0) continue;
        const ErrorSweepRow& finer = sweep->rows[i - 1];
        // Cut size is what a ratio buys; the error follows (noise aside).
        EXPECT_LT(row.avg_cut, finer.avg_cut);
        EXPECT_GT(row.rel_err_mean, 0.8 * finer.rel_err_mean);
    }
    EXPECT_LT(sweep->rows.front().rel_err_mean, 0.01);
    EXPECT_LT(sweep->rows.front().rel_err_mean, 0.5 * sweep->rows.back().rel_err_mean);
    // The fixed 2% yardstick: above the row's own ratio it counts fewer pixels
    // than "over E", below it more; the finest ratio has the fewest.
    for (const ErrorSweepRow& row : sweep->rows) {
        EXPECT_GE(row.frac_over_2pct, 0.0);
        EXPECT_LE(row.frac_over_2pct, 1.0);
        if (row.error_ratio < 0.02f) {
            EXPECT_LE(row.frac_over_2pct, row.frac_over_error);
        }
        if (row.error_ratio > 0.02f) {
            EXPECT_GE(row.frac_over_2pct, row.frac_over_error);
        }
    }
    EXPECT_LT(sweep->rows.front().frac_over_2pct, sweep->rows.back().frac_over_2pct);
    EXPECT_FALSE(sweep->shadows) << "the empty room needs no shadow rays";

    // The CSV: a header and one row per ratio, the ratio in its column.
    const std::filesystem::path csv =
        std::filesystem::temp_directory_path() / "lc_error_sweep_test.csv";
    ASSERT_TRUE(write_error_sweep_csv(csv, *sweep).ok());
    std::ifstream in(csv);
    std::string header, line;
    std::getline(in, header);
    EXPECT_EQ(header.rfind("lights,shadows,reference_ms,error_ratio,", 0), 0u) << header;
    size_t rows = 0;
    while (std::getline(in, line)) {
        EXPECT_EQ(line.rfind("1500,0,", 0), 0u) << line;
        ++rows;
    }
    EXPECT_EQ(rows, ratios.size());
    std::filesystem::remove(csv);
    EXPECT_FALSE(write_error_sweep_csv("/nonexistent-dir/x.csv", *sweep).ok());
}

}  // namespace
}  // namespace lc::client
