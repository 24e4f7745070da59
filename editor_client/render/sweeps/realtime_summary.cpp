// The real-time sweep's summary: each variant at the cheapest one's time and rays, and on the path.
#include "editor_client/render/sweeps/realtime_sweep.h"

#include <algorithm>
#include <limits>
#include <string>

#include "editor_client/render/sweeps/equal_budget.h"

namespace lc::client {
namespace {

// A variant's still rows as cumulative (cost, error) points.
std::vector<CostErrorPoint> still_points(const RealtimeSweep& sweep, const std::string& label, bool by_rays,
                                         bool mean_error) {
    std::vector<CostErrorPoint> points;
    for (const RealtimeSweepRow& r : sweep.rows) {
        if (r.moving || r.label != label) continue;
        const double cost = by_rays ? r.shadow_rays_per_pixel * double(r.frames) : r.total_ms;
        points.push_back({cost, mean_error ? r.rel_err_mean : r.rel_mse});
    }
    return points;
}

const RealtimeSweepRow* last_still_row(const RealtimeSweep& sweep, const std::string& label) {
    const RealtimeSweepRow* last = nullptr;
    for (const RealtimeSweepRow& r : sweep.rows) {
        if (!r.moving && r.label == label) last = &r;
    }
    return last;
}

// Means over a variant's path frames: frame time, relative MSE, mean error.
void add_path_means(const RealtimeSweep& sweep, RealtimeSweepSummary& summary) {
    double ms = 0.0, mse = 0.0, err = 0.0;
    uint32_t frames = 0;
    for (const RealtimeSweepRow& r : sweep.rows) {
        if (!r.moving || r.label != summary.label) continue;
        ms += r.frame_ms;
        mse += r.rel_mse;
        err += r.rel_err_mean;
        ++frames;
    }
    const double none = std::numeric_limits<double>::quiet_NaN();
    summary.path_frame_ms = frames ? ms / frames : none;
    summary.path_rel_mse = frames ? mse / frames : none;
    summary.path_err_mean = frames ? err / frames : none;
}

// The path's MSE had the variant's frame cost what the baseline's did: noise
// scales with the time spent; a variant that does not accumulate (biased,
// the same image at any time) keeps its error, if its frame fits the time at all.
double path_mse_at_time(const RealtimeVariant& variant, const RealtimeSweepSummary& summary, double baseline_ms) {
    if (variant.accumulates) return summary.path_rel_mse * summary.path_frame_ms / baseline_ms;
    return summary.path_frame_ms <= baseline_ms ? summary.path_rel_mse : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

void summarize_realtime_sweep(RealtimeSweep& sweep, const std::vector<RealtimeVariant>& variants) {
    sweep.summaries.clear();
    const RealtimeSweepRow* cheapest = nullptr;
    for (const RealtimeVariant& variant : variants) {
        const RealtimeSweepRow* last = last_still_row(sweep, variant.label);
        if (last != nullptr && (cheapest == nullptr || last->frame_ms < cheapest->frame_ms)) cheapest = last;
    }
    if (cheapest == nullptr) return;
    sweep.baseline = cheapest->label;
    sweep.budget_ms = cheapest->total_ms;
    sweep.budget_rays = cheapest->shadow_rays_per_pixel * double(cheapest->frames);
    double baseline_path_ms = 0.0;
    for (const RealtimeVariant& variant : variants) {
        RealtimeSweepSummary summary;
        summary.label = variant.label;
        const RealtimeSweepRow* last = last_still_row(sweep, variant.label);
        summary.frame_ms = last ? last->frame_ms : 0.0;
        summary.equal_time_rel_mse = error_at_budget(still_points(sweep, variant.label, false, false), sweep.budget_ms);
        summary.equal_time_err_mean = error_at_budget(still_points(sweep, variant.label, false, true), sweep.budget_ms);
        summary.equal_rays_rel_mse =
            error_at_budget(still_points(sweep, variant.label, true, false), sweep.budget_rays);
        add_path_means(sweep, summary);
        if (variant.label == sweep.baseline) baseline_path_ms = summary.path_frame_ms;
        sweep.summaries.push_back(summary);
    }
    for (size_t i = 0; i < variants.size(); ++i)
        sweep.summaries[i].path_equal_time_rel_mse = path_mse_at_time(variants[i], sweep.summaries[i], baseline_path_ms);
}

Status write_realtime_summary_csv(const std::filesystem::path& path, const RealtimeSweep& sweep) {
    std::FILE* out = std::fopen(path.string().c_str(), "w");
    if (out == nullptr) return make_error("cannot write the real-time summary to " + path.string());
    std::fprintf(out,
                 "variant,baseline,budget_ms,budget_rays,frame_ms,equal_time_rel_mse,equal_time_err_mean,"
                 "equal_rays_rel_mse,path_frame_ms,path_rel_mse,path_err_mean,path_equal_time_rel_mse\n");
    for (const RealtimeSweepSummary& s : sweep.summaries) {
        std::fprintf(out, "%s,%s,%.1f,%.2f,%.2f,%.6g,%.5f,%.6g,%.2f,%.6g,%.5f,%.6g\n", s.label.c_str(),
                     sweep.baseline.c_str(), sweep.budget_ms, sweep.budget_rays, s.frame_ms, s.equal_time_rel_mse,
                     s.equal_time_err_mean, s.equal_rays_rel_mse, s.path_frame_ms, s.path_rel_mse, s.path_err_mean,
                     s.path_equal_time_rel_mse);
    }
    if (std::fclose(out) != 0) return make_error("cannot write the real-time summary to " + path.string());
    return Ok{};
}

std::filesystem::path realtime_summary_path(const std::filesystem::path& sweep_csv) {
    std::filesystem::path summary = sweep_csv;
    summary.replace_filename(sweep_csv.stem().string() + "_equal" + sweep_csv.extension().string());
    return summary;
}

}  // namespace lc::client
