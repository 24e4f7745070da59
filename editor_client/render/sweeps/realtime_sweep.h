#pragma once
// What the real-time mode's accuracy costs in time on one scene and camera:
// for each cut size K, the frames of a still view accumulated, measured
// against one reference frame of the same run after 1, 4, 16, ... frames.
// `editor_client render --mode realtime --sweep-realtime 8,16,32` prints it
// (the real-time counterpart of --sweep-error).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string_view>
#include <vector>

#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/renderer.h"
#include "lightcuts/result.h"

namespace lc::client {

struct RealtimeSweepRow {
    uint32_t cut = 0;     // K
    uint32_t rays = 0;    // the budget asked for (0: one per cut node)
    uint32_t frames = 0;  // accumulated so far
    double frame_ms = 0.0;  // mean GPU time of those frames
    double total_ms = 0.0;  // their sum
    double shadow_rays_per_pixel = 0.0;  // per lit pixel and frame, the last frame's
    double rel_mse = 0.0;  // sum of squared differences over the reference's, lit pixels
    double rel_err_mean = 0.0;
    double rel_err_p99 = 0.0;
    double frac_over_2pct = 0.0;
    double max_err = 0.0;
};

struct RealtimeSweep {
    double reference_ms = 0.0;
    uint64_t lights = 0;
    bool shadows = false;
    std::vector<RealtimeSweepRow> rows;
};

// "8,16,32": integers in [min, max], at least one, ascending; `flag` names the option.
Result<std::vector<uint32_t>> parse_count_list(std::string_view text, std::string_view flag, uint32_t min,
                                               uint32_t max);

// Renders the reference once, then for each cut size the real-time frames of
// the still view, measuring the accumulated image at each count of
// `frame_counts` (ascending). Each cut size starts a history of its own, and
// the next real-time frame after the sweep does too.
Result<RealtimeSweep> run_realtime_sweep(Renderer& renderer, const RenderSettings& settings,
                                         const std::vector<uint32_t>& cuts,
                                         const std::vector<uint32_t>& frame_counts);

void print_realtime_sweep(std::FILE* out, const RealtimeSweep& sweep);
// One row per cut size and frame count (columns named in the header line).
Status write_realtime_sweep_csv(const std::filesystem::path& path, const RealtimeSweep& sweep);

}  // namespace lc::client
