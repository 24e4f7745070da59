#pragma once
// The real-time modes side by side on one scene (issue 38): for each variant
// (realtime_variant.h), the frames of a still view accumulated and measured
// against one reference frame after 1, 4, 16, ... frames, then the frames of
// a scripted moving camera (camera_path.h), each against its own reference,
// the history kept along the path as a user would see it; then each
// variant's error at the time and the rays the cheapest one spent.
// `editor_client render --mode realtime --sweep-realtime lc,K8r1,K16` prints it.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "editor_client/render/renderer.h"
#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/sweeps/realtime_variant.h"
#include "lightcuts/result.h"

namespace lc::client {

struct RealtimeSweepRow {
    std::string label;  // the variant's
    RenderMode mode = RenderMode::kRealtime;
    uint32_t cut = 0;   // K (realtime)
    uint32_t rays = 0;  // the budget asked for (0: one per cut node)
    bool moving = false;  // a frame of the camera path (else the still view's accumulation)
    uint32_t frames = 0;  // still: frames accumulated; moving: the path frame, from 1
    double frame_ms = 0.0;  // still: mean GPU time of those frames; moving: this frame's
    double total_ms = 0.0;  // their sum (moving: the path's so far)
    double shadow_rays_per_pixel = 0.0;  // per lit pixel and frame, the last frame's
    double rel_mse = 0.0;  // sum of squared differences over the reference's, lit pixels
    double rel_err_mean = 0.0;
    double rel_err_p99 = 0.0;
    double frac_over_2pct = 0.0;
    double max_err = 0.0;
};

// A variant's standing against the cheapest one (the baseline).
struct RealtimeSweepSummary {
    std::string label;
    double frame_ms = 0.0;  // still view, mean
    double equal_time_rel_mse = 0.0;  // after the baseline's total time (NaN: out of the measured range)
    double equal_time_err_mean = 0.0;
    double equal_rays_rel_mse = 0.0;  // after the baseline's shadow rays per pixel
    double path_frame_ms = 0.0;  // moving camera, means over the path's frames
    double path_rel_mse = 0.0;
    double path_err_mean = 0.0;
    // The path's MSE at the baseline's frame time: path_rel_mse x path_frame_ms
    // / the baseline's (noise whose variance falls as 1 / samples); a variant
    // that does not accumulate keeps its MSE where its frame fits that time (else NaN).
    double path_equal_time_rel_mse = 0.0;
};

struct RealtimeSweep {
    double reference_ms = 0.0;
    uint64_t lights = 0;
    bool shadows = false;
    std::string baseline;  // the label of the variant with the cheapest still frame
    double budget_ms = 0.0;    // its total time over the largest frame count
    double budget_rays = 0.0;  // and its shadow rays per pixel
    std::vector<RealtimeSweepRow> rows;
    std::vector<RealtimeSweepSummary> summaries;  // one per variant, in order
};

// "8,16,32": integers in [min, max], at least one, ascending; `flag` names the option.
Result<std::vector<uint32_t>> parse_count_list(std::string_view text, std::string_view flag, uint32_t min,
                                               uint32_t max);

struct RealtimeSweepPlan {
    std::vector<RealtimeVariant> variants;
    std::vector<uint32_t> frame_counts;  // ascending
    uint32_t path_frames = 0;  // 0: no moving camera
};

// Renders the references (the still view's, then one per path frame), then
// each variant's still and moving frames, each variant's from a history of
// its own; the next real-time frame after the sweep starts one too.
Result<RealtimeSweep> run_realtime_sweep(Renderer& renderer, const RenderSettings& settings,
                                         const RealtimeSweepPlan& plan);

// Fills sweep.summaries, the baseline and its budgets from sweep.rows.
void summarize_realtime_sweep(RealtimeSweep& sweep, const std::vector<RealtimeVariant>& variants);

void print_realtime_sweep(std::FILE* out, const RealtimeSweep& sweep);
// One row per variant and frame count, then per variant and path frame (columns named in the header line).
Status write_realtime_sweep_csv(const std::filesystem::path& path, const RealtimeSweep& sweep);
// One row per variant: its standing at equal time and rays, and on the moving path.
Status write_realtime_summary_csv(const std::filesystem::path& path, const RealtimeSweep& sweep);
// Where write_realtime_summary_csv goes beside the sweep's CSV: OUT.csv -> OUT_equal.csv.
std::filesystem::path realtime_summary_path(const std::filesystem::path& sweep_csv);

}  // namespace lc::client
