#include "editor_client/render/sweeps/realtime_sweep.h"

#include <algorithm>
#include <charconv>
#include <string>

#include "editor_client/render/analysis/error_stats.h"
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

// The accumulated image after `frames` frames, measured.
Result<RealtimeSweepRow> measure(Renderer& renderer, const RenderSettings& settings,
                                 const std::vector<float>& reference, const RenderStats& last) {
    Result<std::vector<float>> image = renderer.read_hdr();
    if (!image) return make_error(image.error());
    Result<ErrorStats> errors = compute_error_stats(*image, reference, settings.width, settings.height, 0.02);
    if (!errors) return make_error(errors.error());
    RealtimeSweepRow row;
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

// One cut size: frames until each count of `frame_counts`, measured there.
Status sweep_cut(Renderer& renderer, RenderSettings settings, const std::vector<float>& reference,
                 const std::vector<uint32_t>& frame_counts, RealtimeSweep& sweep) {
    // A whole frame first, not counted: a CPU device compiles the shaders for
    // the first dispatch of each size (1.9 s of llvmpipe's first 48x48 frame).
    LC_RETURN_IF_ERROR(renderer.warm_up(settings));
    if (Result<RenderStats> first = renderer.render(settings); !first) return make_error(first.error());
    renderer.restart_realtime();
    uint32_t frames = 0;
    double total_ms = 0.0;
    RenderStats last;
    for (uint32_t target : frame_counts) {
        for (; frames < target; ++frames) {
            Result<RenderStats> stats = renderer.render(settings);
            if (!stats) return make_error("cut " + std::to_string(settings.realtime_cut) + ": " + stats.error());
            total_ms += stats->timing.render_ms;
            last = *stats;
        }
        Result<RealtimeSweepRow> row = measure(renderer, settings, reference, last);
        if (!row) return make_error(row.error());
        row->frames = frames;
        row->total_ms = total_ms;
        row->frame_ms = total_ms / double(frames);
        sweep.rows.push_back(*row);
    }
    return Ok{};
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
                                         const std::vector<uint32_t>& cuts,
                                         const std::vector<uint32_t>& frame_counts) {
    RealtimeSweep sweep;
    Result<ReferenceFrame> reference = render_reference_frame(renderer, settings);
    if (!reference) return make_error(reference.error());
    sweep.reference_ms = reference->stats.timing.render_ms;
    sweep.lights = reference->stats.lights;
    sweep.shadows = reference->stats.shadows.simulated;
    RenderSettings realtime = settings;
    realtime.mode = RenderMode::kRealtime;
    for (uint32_t cut : cuts) {
        realtime.realtime_cut = cut;
        LC_RETURN_IF_ERROR(sweep_cut(renderer, realtime, reference->image, frame_counts, sweep));
    }
    renderer.restart_realtime();  // the caller's frames are not the sweep's
    return sweep;
}

void print_realtime_sweep(std::FILE* out, const RealtimeSweep& sweep) {
    std::fprintf(out, "reference: %llu lights, %.1f ms GPU%s; the real-time image is the plain mean of its frames\n",
                 (unsigned long long)sweep.lights, sweep.reference_ms, sweep.shadows ? ", with shadow rays" : "");
    std::fprintf(out, "%5s %6s %7s %10s %11s %11s %10s %9s %9s %9s %9s\n", "cut", "rays", "frames",
                 "ms/frame", "ms, all", "rays/pixel", "rel MSE", "err mean", "err p99", "over 2%", "err max");
    for (const RealtimeSweepRow& r : sweep.rows) {
        std::fprintf(out, "%5u %6u %7u %10.1f %11.1f %11.2f %10.3g %9.4f %9.4f %8.2f%% %9.4f\n", r.cut, r.rays,
                     r.frames, r.frame_ms, r.total_ms, r.shadow_rays_per_pixel, r.rel_mse, r.rel_err_mean,
                     r.rel_err_p99, 100.0 * r.frac_over_2pct, r.max_err);
    }
}

Status write_realtime_sweep_csv(const std::filesystem::path& path, const RealtimeSweep& sweep) {
    std::FILE* out = std::fopen(path.string().c_str(), "w");
    if (out == nullptr) return make_error("cannot write the real-time sweep to " + path.string());
    std::fprintf(out,
                 "lights,shadows,reference_ms,realtime_cut,realtime_rays,frames,frame_ms,total_ms,"
                 "shadow_rays_per_pixel,rel_mse,rel_err_mean,rel_err_p99,frac_over_2pct,max_err\n");
    for (const RealtimeSweepRow& r : sweep.rows) {
        std::fprintf(out, "%llu,%d,%.1f,%u,%u,%u,%.2f,%.1f,%.3f,%.6g,%.5f,%.5f,%.5f,%.4f\n",
                     (unsigned long long)sweep.lights, sweep.shadows ? 1 : 0,
                     sweep.reference_ms, r.cut, r.rays, r.frames, r.frame_ms, r.total_ms, r.shadow_rays_per_pixel,
                     r.rel_mse, r.rel_err_mean, r.rel_err_p99, r.frac_over_2pct, r.max_err);
    }
    if (std::fclose(out) != 0) return make_error("cannot write the real-time sweep to " + path.string());
    return Ok{};
}

}  // namespace lc::client
