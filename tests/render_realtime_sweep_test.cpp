// `render --mode realtime --sweep-realtime`: the real-time mode's price of
// accuracy on one scene, each cut size's accumulated frames measured against
// one reference frame (editor_client/render/sweeps/realtime_sweep.h).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "editor_client/render/sweeps/realtime_sweep.h"
#include "editor_client/render/renderer.h"
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

using RealtimeSweepRender = test::VulkanTest;

TEST_F(RealtimeSweepRender, MoreFramesErrLessAndTheBudgetHolds) {
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
    Result<RealtimeSweep> sweep = run_realtime_sweep(**renderer, settings, {4, 8}, {2, 8, 32});
    ASSERT_TRUE(sweep.ok()) << sweep.error();
    print_realtime_sweep(stdout, *sweep);
    ASSERT_EQ(sweep->rows.size(), 6u);
    EXPECT_GT(sweep->reference_ms, 0.0);
    RenderSettings next = settings;
    next.mode = RenderMode::kRealtime;
    next.realtime_cut = 8;  // the sweep's last
    ASSERT_TRUE((*renderer)->render(next).ok());
    EXPECT_EQ((*renderer)->realtime_frames(), 1u) << "the sweep's history is not the caller's";
    for (size_t i = 0; i < sweep->rows.size(); ++i) {
        const RealtimeSweepRow& r = sweep->rows[i];
        EXPECT_EQ(r.cut, i < 3 ? 4u : 8u);
        EXPECT_EQ(r.frames, (std::vector<uint32_t>{2, 8, 32})[i % 3]);
        EXPECT_LE(r.shadow_rays_per_pixel, 2.0) << "at most the budget's rays a lit pixel";
        EXPECT_GT(r.shadow_rays_per_pixel, 1.0);
        EXPECT_GT(r.total_ms, 0.0);
        // 16x the frames: the unbiased mean's squared error falls about 16x.
        if (i % 3 == 2) {
            EXPECT_LT(r.rel_mse, sweep->rows[i - 2].rel_mse / 4.0) << "cut " << r.cut;
        }
    }
    const std::filesystem::path csv = std::filesystem::temp_directory_path() / "lc_realtime_sweep_test.csv";
    ASSERT_TRUE(write_realtime_sweep_csv(csv, *sweep).ok());
    std::ifstream in(csv);
    std::string line;
    int lines = 0;
    while (std::getline(in, line)) ++lines;
    EXPECT_EQ(lines, 7) << "a header and a row per cut size and frame count";
    std::filesystem::remove(csv);
}

}  // namespace
}  // namespace lc::client
