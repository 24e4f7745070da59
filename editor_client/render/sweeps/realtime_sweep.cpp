#include "editor_client/render/sweeps/realtime_sweep.h"

#include <algorithm>
#include <charconv>
#include <string>

#include "editor_client/render/analysis/error_stats.h"
#include "editor_client/render/sweeps/camera_path.h"
#include "editor_client/render/sweeps/error_sweep.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

// Lit pixels' squared error over their squared reference (alpha 0: background).
double relative_mse(const std::vector<float>& image, const std::vector<float>& reference) {
    double error = 0.0, energy = 0.0;
    for (size_t i = 0; i + 3 < image.size() && i + 3 < reference.size(); i += 4) {
        if (reference[i + 3] == 0.0f) continue;
        for (size_t c = 0; c < 3; ++c) {
            const double d = double(image[i + c]) - double(reference[i + c]);
            error += d * d;
            energy += double(reference[i + c]) * double(reference[i + c]);
        }
    }
    return energy > 0.0 ? error / energy : 0.0;
}

// The image shown after the last frame, measured.
Result<RealtimeSweepRow> measure(Renderer& renderer, const RenderSettings& settings, const std::string& label,
                                 const std::vector<float>& reference, const RenderStats& last) {
    Result<std::vector<float>> image = renderer.read_hdr();
    if (!image) return make_error(image.error());
    Result<ErrorStats> errors = compute_error_stats(*image, reference, settings.width, settings.height, 0.02);
    if (!errors) return make_error(errors.error());
    RealtimeSweepRow row;
    row.label = label;
    row.mode = settings.mode;
    row.cut = settings.realtime_cut;
    row.rays = settings.realtime_rays;
    row.shadow_rays_per_pixel = double(last.shadows.rays) / double(std::max<uint64_t>(last.geometry_pixels, 1));
    row.rel_mse = relative_mse(*image, reference);
    row.rel_err_mean = errors->rel_err_mean;
    row.rel_err_p99 = errors->rel_err_p99;
    row.frac_over_2pct = errors->frac_over_error;
    row.max_err = errors->max_err;
    return row;
}

Result<RenderStats> render_frame(Renderer& renderer, const RenderSettings& settings, const std::string& label) {
    Result<RenderStats> stats = renderer.render(settings);
    if (!stats) return make_error(label + ": " + stats.error());
    return stats;
}

// A whole frame first, not counted: a CPU device compiles the shaders for
// the first dispatch of each size (1.9 s of llvmpipe's first 48x48 frame).
Status warm_up(Renderer& renderer, const RenderSettings& settings, const std::string& label) {
    LC_RETURN_IF_ERROR(renderer.warm_up(settings));
    if (Result<RenderStats> first = render_frame(renderer, settings, label); !first) return make_error(first.error());
    renderer.restart_realtime();
    return Ok{};
}

// The still view: frames until each count, measured there. A variant that
// does not accumulate renders its frames until the first count only: its
// image, and so its error, is the same at every count, and its time adds up.
Status sweep_still(Renderer& renderer, const RenderSettings& settings, const RealtimeVariant& variant,
                   const std::vector<float>& reference, const std::vector<uint32_t>& frame_counts,
                   RealtimeSweep& sweep) {
    uint32_t frames = 0;
    double total_ms = 0.0;
    RenderStats last;
    for (uint32_t target : frame_counts) {
        const uint32_t rendered = variant.accumulates ? target : frame_counts.front();
        for (; frames < rendered; ++frames) {
            Result<RenderStats> stats = render_frame(renderer, settings, variant.label);
            if (!stats) return make_error(stats.error());
            total_ms += stats->timing.render_ms;
            last = *stats;
        }
        Result<RealtimeSweepRow> row = measure(renderer, settings, variant.label, reference, last);
        if (!row) return make_error(row.error());
        row->frames = target;
        row->frame_ms = total_ms / double(frames);
        row->total_ms = row->frame_ms * double(target);
        sweep.rows.push_back(*row);
    }
    return Ok{};
}

// The moving camera: one frame per path camera, the history kept, each measured against its reference.
Status sweep_path(Renderer& renderer, RenderSettings settings, const RealtimeVariant& variant,
                  const std::vector<RenderCamera>& path, const std::vector<std::vector<float>>& references,
                  RealtimeSweep& sweep) {
    renderer.restart_realtime();
    double total_ms = 0.0;
    for (size_t i = 0; i < path.size(); ++i) {
        settings.camera = path[i];
        Result<RenderStats> stats = render_frame(renderer, settings, variant.label);
        if (!stats) return make_error(stats.error());
        total_ms += stats->timing.render_ms;
        Result<RealtimeSweepRow> row = measure(renderer, settings, variant.label, references[i], *stats);
        if (!row) return make_error(row.error());
        row->moving = true;
        row->frames = uint32_t(i + 1);
        row->frame_ms = stats->timing.render_ms;
        row->total_ms = total_ms;
        sweep.rows.push_back(*row);
    }
    return Ok{};
}

Result<std::vector<std::vector<float>>> render_path_references(Renderer& renderer, RenderSettings settings,
                                                               const std::vector<RenderCamera>& path) {
    std::vector<std::vector<float>> references;
    for (const RenderCamera& camera : path) {
        settings.camera = camera;
        Result<ReferenceFrame> reference = render_reference_frame(renderer, settings);
        if (!reference) return make_error("the path's reference: " + reference.error());
        references.push_back(std::move(reference->image));
    }
    return references;
}

}  // namespace

Result<std::vector<uint32_t>> parse_count_list(std::string_view text, std::string_view flag, uint32_t min,
                                               uint32_t max) {
    std::vector<uint32_t> values;
    for (std::string_view view : split_sweep_list(text)) {
        const std::string item(view);
        uint32_t value = 0;
        const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
        if (item.empty() || ec != std::errc() || end != item.data() + item.size() || value < min ||
            value > max || (!values.empty() && value <= values.back()))
            return make_error(std::string(flag) + ": '" + item + "' is not an integer in " + std::to_string(min) +
                              " .. " + std::to_string(max) + " above the one before it");
        values.push_back(value);
    }
    return values;
}

Result<RealtimeSweep> run_realtime_sweep(Renderer& renderer, const RenderSettings& settings,
                                         const RealtimeSweepPlan& plan) {
    if (plan.variants.empty() || plan.frame_counts.empty())
        return make_error("the real-time sweep needs a variant and a frame count");
    RealtimeSweep sweep;
    Result<ReferenceFrame> reference = render_reference_frame(renderer, settings);
    if (!reference) return make_error(reference.error());
    sweep.reference_ms = reference->stats.timing.render_ms;
    sweep.lights = reference->stats.lights;
    sweep.shadows = reference->stats.shadows.simulated;
    const std::vector<RenderCamera> path = orbit_path(settings.camera, plan.path_frames);
    Result<std::vector<std::vector<float>>> path_references = render_path_references(renderer, settings, path);
    if (!path_references) return make_error(path_references.error());
    for (const RealtimeVariant& variant : plan.variants) {
        const RenderSettings variant_frame = variant_settings(variant, settings);
        LC_RETURN_IF_ERROR(warm_up(renderer, variant_frame, variant.label));
        LC_RETURN_IF_ERROR(sweep_still(renderer, variant_frame, variant, reference->image, plan.frame_counts, sweep));
        LC_RETURN_IF_ERROR(sweep_path(renderer, variant_frame, variant, path, *path_references, sweep));
    }
    renderer.restart_realtime();  // the caller's frames are not the sweep's
    summarize_realtime_sweep(sweep, plan.variants);
    return sweep;
}

void print_realtime_sweep(std::FILE* out, const RealtimeSweep& sweep) {
    std::fprintf(out, "reference: %llu lights, %.1f ms GPU%s; the real-time image is the plain mean of its frames\n",
                 (unsigned long long)sweep.lights, sweep.reference_ms, sweep.shadows ? ", with shadow rays" : "");
    std::fprintf(out, "%-9s %-6s %7s %10s %11s %11s %10s %9s %9s %9s %9s\n", "variant", "camera", "frames",
                 "ms/frame", "ms, all", "rays/pixel", "rel MSE", "err mean", "err p99", "within 2%", "err max");
    for (const RealtimeSweepRow& r : sweep.rows) {
        std::fprintf(out, "%-9s %-6s %7u %10.1f %11.1f %11.2f %10.3g %9.4f %9.4f %8.2f%% %9.4f\n", r.label.c_str(),
                     r.moving ? "moving" : "still", r.frames, r.frame_ms, r.total_ms, r.shadow_rays_per_pixel,
                     r.rel_mse, r.rel_err_mean, r.rel_err_p99, 100.0 * (1.0 - r.frac_over_2pct), r.max_err);
    }
    std::fprintf(out,
                 "at equal cost: the still view's error after the %.1f ms and %.1f shadow rays a pixel that %s "
                 "spent (log-log between measured frame counts; nan: not within them); moving: means over the path,\n"
                 "its MSE at %s's frame time = MSE x ms / %s's ms (a mode that does not accumulate: its MSE if its frame fits)\n",
                 sweep.budget_ms, sweep.budget_rays, sweep.baseline.c_str(), sweep.baseline.c_str(),
                 sweep.baseline.c_str());
    std::fprintf(out, "%-9s %10s %14s %14s %14s %12s %12s %14s\n", "variant", "ms/frame", "MSE equal ms",
                 "err equal ms", "MSE equal rays", "moving ms", "moving MSE", "moving MSE eq");
    for (const RealtimeSweepSummary& s : sweep.summaries) {
        std::fprintf(out, "%-9s %10.1f %14.4g %14.4f %14.4g %12.1f %12.4g %14.4g\n", s.label.c_str(), s.frame_ms,
                     s.equal_time_rel_mse, s.equal_time_err_mean, s.equal_rays_rel_mse, s.path_frame_ms,
                     s.path_rel_mse, s.path_equal_time_rel_mse);
    }
}

Status write_realtime_sweep_csv(const std::filesystem::path& path, const RealtimeSweep& sweep) {
    std::FILE* out = std::fopen(path.string().c_str(), "w");
    if (out == nullptr) return make_error("cannot write the real-time sweep to " + path.string());
    std::fprintf(out,
                 "variant,mode,camera,lights,shadows,reference_ms,realtime_cut,realtime_rays,frames,frame_ms,total_ms,"
                 "shadow_rays_per_pixel,rel_mse,rel_err_mean,rel_err_p99,frac_over_2pct,within_2pct,max_err\n");
    for (const RealtimeSweepRow& r : sweep.rows) {
        std::fprintf(out, "%s,%s,%s,%llu,%d,%.1f,%u,%u,%u,%.2f,%.1f,%.3f,%.6g,%.5f,%.5f,%.5f,%.5f,%.4f\n",
                     r.label.c_str(), render_mode_name(r.mode), r.moving ? "moving" : "still",
                     (unsigned long long)sweep.lights, sweep.shadows ? 1 : 0, sweep.reference_ms, r.cut, r.rays,
                     r.frames, r.frame_ms, r.total_ms, r.shadow_rays_per_pixel, r.rel_mse, r.rel_err_mean,
                     r.rel_err_p99, r.frac_over_2pct, 1.0 - r.frac_over_2pct, r.max_err);
    }
    if (std::fclose(out) != 0) return make_error("cannot write the real-time sweep to " + path.string());
    return Ok{};
}

}  // namespace lc::client
