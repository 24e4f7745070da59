#pragma once
// The price of accuracy on one scene and camera: lightcuts rendered at several
// error ratios, each measured against one reference frame of the same run.
// `editor_client render --sweep-error 0.005,0.01,0.02,0.05` prints it.
#include <cstdio>
#include <filesystem>
#include <string_view>
#include <vector>

#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/renderer.h"
#include "lightcuts/result.h"

namespace lc::client {

struct ErrorSweepRow {
    float error_ratio = 0.0f;
    double render_ms = 0.0;  // GPU time of the lightcuts frame
    double wall_ms = 0.0;
    double avg_cut = 0.0;
    uint32_t cut_p99 = 0;
    uint64_t max_cut_hits = 0;
    double rel_err_mean = 0.0;
    double rel_err_p99 = 0.0;
    double frac_over_error = 0.0;  // pixels whose error exceeds this row's ratio
    double frac_over_2pct = 0.0;   // pixels whose error exceeds 2% (a fixed visibility yardstick)
    double max_err = 0.0;
    uint64_t shadow_rays = 0;
    uint64_t loop_limit_stops = 0;
    // GPU reconstruction cuts' block side (0: a lightcut per pixel), the
    // frame's shadow rays per pixel with geometry and the pixels that fell back.
    uint32_t reconstruction_block = 0;
    double shadow_rays_per_pixel = 0.0;
    uint64_t reconstruction_fallbacks = 0;
};

struct ErrorSweep {
    double reference_ms = 0.0;  // GPU time of the reference frame
    double reference_wall_ms = 0.0;
    uint64_t lights = 0;
    uint64_t reference_shadow_rays = 0;
    bool shadows = false;
    std::vector<ErrorSweepRow> rows;
};

// One reference frame of `settings`' view (after a warm-up) and its image:
// what a sweep measures against.
struct ReferenceFrame {
    RenderStats stats;
    std::vector<float> image;
};
Result<ReferenceFrame> render_reference_frame(Renderer& renderer, const RenderSettings& settings);

// "0.005,0.01,0.02": finite ratios >= 0, at least one.
Result<std::vector<float>> parse_error_list(std::string_view text);

// A sweep flag's comma-separated list split into its items, empty ones kept
// ("", "1,,2", a trailing comma), so that the parsers refuse them by name.
std::vector<std::string_view> split_sweep_list(std::string_view text);

// Renders the reference once, then lightcuts (settings' criterion, max cut and
// search) at each ratio: a lightcut per pixel, then reconstruction cuts with
// each block side of `blocks` (empty: settings.reconstruction_block where it
// is not 0). Leaves the renderer holding the last lightcuts frame.
Result<ErrorSweep> run_error_sweep(Renderer& renderer, const RenderSettings& settings,
                                   const std::vector<float>& error_ratios,
                                   const std::vector<uint32_t>& blocks = {});

// The table a user reads: one row per ratio, the reference time on top.
// One row per ratio, with the reference's figures repeated (columns named in
// the header line).
Status write_error_sweep_csv(const std::filesystem::path& path, const ErrorSweep& sweep);
void print_error_sweep(std::FILE* out, const ErrorSweep& sweep);

}  // namespace lc::client
