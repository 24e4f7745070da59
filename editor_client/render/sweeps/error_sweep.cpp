#include "editor_client/render/sweeps/error_sweep.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include "editor_client/render/analysis/error_stats.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

std::vector<std::string_view> split_sweep_list(std::string_view text) {
    std::vector<std::string_view> items;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        items.push_back(text.substr(start, comma - start));
        start = comma + 1;
    }
    return items;
}

Result<std::vector<float>> parse_error_list(std::string_view text) {
    std::vector<float> ratios;
    for (std::string_view view : split_sweep_list(text)) {
        const std::string item(view);
        float value = 0.0f;
        const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
        if (item.empty() || ec != std::errc() || end != item.data() + item.size() ||
            !std::isfinite(value) || value < 0.0f)
            return make_error("--sweep-error: '" + item +
                              "' is not a finite error ratio >= 0 (expected e.g. "
                              "0.005,0.01,0.02,0.05)");
        ratios.push_back(value);
    }
    return ratios;
}

Result<ReferenceFrame> render_reference_frame(Renderer& renderer, const RenderSettings& settings) {
    RenderSettings reference_settings = settings;
    reference_settings.mode = RenderMode::kReference;
    LC_RETURN_IF_ERROR(renderer.warm_up(reference_settings));
    Result<RenderStats> stats = renderer.render(reference_settings);
    if (!stats) return make_error("reference: " + stats.error());
    Result<std::vector<float>> image = renderer.read_hdr();
    if (!image) return make_error(image.error());
    return ReferenceFrame{std::move(stats).value(), std::move(image).value()};
}

namespace {

// One lightcuts frame of `settings` measured against the reference image.
Result<ErrorSweepRow> measure_lightcuts(Renderer& renderer, const RenderSettings& settings,
                                        const std::vector<float>& reference) {
    const float ratio = settings.error_ratio;
    LC_RETURN_IF_ERROR(renderer.warm_up(settings));
    Result<RenderStats> stats = renderer.render(settings);
    if (!stats) return make_error("error ratio " + std::to_string(ratio) + ": " + stats.error());
    Result<std::vector<float>> hdr = renderer.read_hdr();
    if (!hdr) return make_error(hdr.error());
    Result<ErrorStats> errors = compute_error_stats(*hdr, reference, settings.width, settings.height, ratio);
    if (!errors) return make_error(errors.error());
    ErrorSweepRow row;
    row.error_ratio = ratio;
    row.render_ms = stats->timing.render_ms;
    row.wall_ms = stats->timing.wall_ms;
    row.avg_cut = stats->cuts.avg_cut;
    row.cut_p99 = stats->cuts.cut_p99;
    row.max_cut_hits = stats->cuts.max_cut_hits;
    row.rel_err_mean = errors->rel_err_mean;
    row.rel_err_p99 = errors->rel_err_p99;
    row.frac_over_error = errors->frac_over_error;
    row.frac_over_2pct = fraction_over(*errors, 0.02);
    row.max_err = errors->max_err;
    row.shadow_rays = stats->shadows.rays;
    row.loop_limit_stops = stats->cuts.loop_limit_stops;
    row.reconstruction_block = settings.reconstruction_block;
    row.shadow_rays_per_pixel =
        stats->geometry_pixels > 0 ? double(stats->shadows.rays) / double(stats->geometry_pixels) : 0.0;
    row.reconstruction_fallbacks = stats->reconstruction.fallbacks;
    return row;
}

}  // namespace

Result<ErrorSweep> run_error_sweep(Renderer& renderer, const RenderSettings& settings,
                                   const std::vector<float>& error_ratios,
                                   const std::vector<uint32_t>& blocks) {
    ErrorSweep sweep;
    Result<ReferenceFrame> frame = render_reference_frame(renderer, settings);
    if (!frame) return make_error(frame.error());
    const std::vector<float>* reference = &frame->image;
    sweep.reference_ms = frame->stats.timing.render_ms;
    sweep.reference_wall_ms = frame->stats.timing.wall_ms;
    sweep.lights = frame->stats.lights;
    sweep.reference_shadow_rays = frame->stats.shadows.rays;
    sweep.shadows = frame->stats.shadows.simulated;

    RenderSettings lightcuts = settings;
    lightcuts.mode = RenderMode::kLightcuts;
    std::vector<uint32_t> rows{0};
    rows.insert(rows.end(), blocks.begin(), blocks.end());
    if (blocks.empty() && settings.reconstruction_block > 0) rows.push_back(settings.reconstruction_block);
    for (float ratio : error_ratios) {
        lightcuts.error_ratio = ratio;
        for (uint32_t block : rows) {
            lightcuts.reconstruction_block = block;
            Result<ErrorSweepRow> row = measure_lightcuts(renderer, lightcuts, *reference);
            if (!row) return make_error(row.error());
            sweep.rows.push_back(*row);
        }
    }
    return sweep;
}

void print_error_sweep(std::FILE* out, const ErrorSweep& sweep) {
    std::fprintf(out, "reference: %llu lights, %.1f ms GPU, %.1f ms wall%s\n",
                 (unsigned long long)sweep.lights, sweep.reference_ms, sweep.reference_wall_ms,
                 sweep.shadows ? ", with shadow rays" : "");
    std::fprintf(out, "%8s %10s %10s %8s %8s %7s %9s %9s %9s %9s %9s %8s %6s %8s\n", "error", "GPU ms",
                 "wall ms", "speedup", "avg cut", "p99 cut", "err mean", "err p99", "over E",
                 "over 2%", "err max", "max-cut", "recon", "rays/px");
    for (const ErrorSweepRow& r : sweep.rows) {
        const double speedup = r.render_ms > 0.0 ? sweep.reference_ms / r.render_ms : 0.0;
        std::fprintf(out,
                     "%8.4g %10.1f %10.1f %7.2fx %8.1f %7u %9.4f %9.4f %8.2f%% %8.2f%% %9.4f %8llu %6s %8.1f\n",
                     r.error_ratio, r.render_ms, r.wall_ms, speedup, r.avg_cut, r.cut_p99,
                     r.rel_err_mean, r.rel_err_p99, 100.0 * r.frac_over_error,
                     100.0 * r.frac_over_2pct, r.max_err, (unsigned long long)r.max_cut_hits,
                     r.reconstruction_block > 0 ? std::to_string(r.reconstruction_block).c_str() : "-",
                     r.shadow_rays_per_pixel);
    }
}

Status write_error_sweep_csv(const std::filesystem::path& path, const ErrorSweep& sweep) {
    std::FILE* out = std::fopen(path.string().c_str(), "w");
    if (out == nullptr) return make_error("cannot write the error sweep to " + path.string());
    std::fprintf(out,
                 "lights,shadows,reference_ms,error_ratio,lightcuts_ms,speedup,avg_cut,cut_p99,"
                 "max_cut_hits,rel_err_mean,rel_err_p99,frac_over_error,frac_over_2pct,max_err,"
                 "reference_shadow_rays,shadow_rays,loop_limit_stops,reconstruction_block,"
                 "shadow_rays_per_pixel,reconstruction_fallbacks\n");
    for (const ErrorSweepRow& r : sweep.rows) {
        const double speedup = r.render_ms > 0.0 ? sweep.reference_ms / r.render_ms : 0.0;
        std::fprintf(out,
                     "%llu,%d,%.1f,%g,%.1f,%.2f,%.1f,%u,%llu,%.5f,%.5f,%.5f,%.5f,%.4f,%llu,%llu,%llu,%u,%.2f,"
                     "%llu\n",
                     (unsigned long long)sweep.lights, sweep.shadows ? 1 : 0, sweep.reference_ms,
                     r.error_ratio, r.render_ms, speedup, r.avg_cut, r.cut_p99,
                     (unsigned long long)r.max_cut_hits, r.rel_err_mean, r.rel_err_p99,
                     r.frac_over_error, r.frac_over_2pct, r.max_err,
                     (unsigned long long)sweep.reference_shadow_rays,
                     (unsigned long long)r.shadow_rays, (unsigned long long)r.loop_limit_stops,
                     r.reconstruction_block, r.shadow_rays_per_pixel,
                     (unsigned long long)r.reconstruction_fallbacks);
    }
    const bool ok = std::fclose(out) == 0;
    if (!ok) return make_error("cannot write the error sweep to " + path.string());
    return Ok{};
}

}  // namespace lc::client
