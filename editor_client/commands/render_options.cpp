#include "editor_client/commands/render_options.h"

#include <string>
#include <vector>

#include "editor_client/commands/enum_flags.h"
#include "lightcuts/device/limits.h"

namespace lc::client {
namespace {

// render --mode's names: the renderer's modes and the error view.
std::vector<std::string> mode_names() {
    std::vector<std::string> names;
    for (const NamedValue<RenderMode>& entry : kRenderModeNames) names.emplace_back(entry.name);
    names.emplace_back(kErrorViewName);
    return names;
}

// --mode: a renderer mode, or the error view (lightcuts, shown as its error).
void add_mode_flag(CLI::App* cmd, RenderOptions* options) {
    auto pick = [options](const std::string& name) {
        options->error_view = name == kErrorViewName;
        options->mode = options->error_view ? RenderMode::kLightcuts : parse_render_mode(name);
    };
    cmd->add_option_function<std::string>(
           "--mode", pick,
           "reference, lightcuts, cuts, cutsize, realtime (stochastic lightcuts with a "
           "fixed shadow-ray budget), restir (ReSTIR DI: resampled candidates reused across "
           "pixels and frames, one shadow ray per pixel) or error (relative error of lightcuts "
           "against the reference, as a heatmap; 0 .. 2 x --error). Default: lightcuts "
           "when a tree source (--tree, --server, --spawn-server) is given, else "
           "reference")
        ->check(CLI::IsMember(mode_names()));
}

// --mode and the cut: criterion, error, search, representatives, shadows.
void add_mode_flags(CLI::App* cmd, RenderOptions* options) {
    add_mode_flag(cmd, options);
    cmd->add_option("--criterion", options->criterion,
                    "Cut criterion: bound (the paper's error bounds) or radius (the thesis)")
        ->transform(checked_names(kCriterionNames))
        ->default_str(criterion_name(options->criterion));
    cmd->add_option("--error", options->error_ratio,
                    "Bound criterion: refine until every node's error bound is <= this x the "
                    "pixel's total")
        ->capture_default_str();
    cmd->add_option("--max-cut", options->max_cut,
                    "Bound criterion: most nodes in a cut (pixels that reach it are counted as "
                    "max_cut_hits)")
        ->capture_default_str();
    cmd->add_option("--bound-search", options->bound_search,
                    "Bound criterion: walk (threshold passes, fast on SIMD devices) or heap (the "
                    "paper's largest-bound-first order); both stop under the same rule")
        ->transform(checked_names(kBoundSearchNames))
        ->default_str(bound_search_name(options->bound_search));
    cmd->add_flag("--share-cuts", options->share_cuts,
                  "Bound criterion, walk search: one cut per subgroup of neighbouring pixels "
                  "(8 on lavapipe), refined until it meets every one of their bounds");
    cmd->add_option("--representative-seed", options->representative_seed,
                    "--representatives pixel or importance: the seed of the per-pixel draws")
        ->capture_default_str();
    add_shared_render_flags(*cmd, options->shared);
}

// --sweep-error and --compare-reference: the error against the reference.
void add_measurement_flags(CLI::App* cmd, RenderOptions* options) {
    cmd->add_option("--sweep-error", options->sweep_error,
                    "Print the price of accuracy on this scene and camera: lightcuts at each "
                    "error ratio of the list (e.g. 0.005,0.01,0.02,0.05) against one reference: "
                    "GPU time, speedup, cut sizes and measured error");
    cmd->add_option("--sweep-blocks", options->sweep_blocks,
                    "With --sweep-error: after each ratio's lightcut per pixel, reconstruction cuts "
                    "(--reconstruction) with each block side of the list (e.g. 4,8)");
    cmd->add_option("--sweep-realtime", options->sweep_realtime,
                    "With --mode realtime: the real-time modes side by side on this scene: for each "
                    "variant of the list (lc or lc0.05: deterministic lightcuts at --error or that "
                    "ratio; K16, K8r1 or 16: stochastic lightcuts at that cut and ray budget; restir or restir16: "
                    "ReSTIR DI with --restir-* or that many candidates) the "
                    "still view's frames accumulated, against one reference, after each count of "
                    "--sweep-frames, then each frame of --sweep-path's orbit against its own, then "
                    "the error at the cheapest variant's time and rays");
    cmd->add_option("--sweep-path", options->sweep_path,
                    "With --sweep-realtime: frames of the moving camera's orbit (0: none)")
        ->capture_default_str();
    cmd->add_option("--sweep-frames", options->sweep_frames,
                    "With --sweep-realtime: the frame counts measured, ascending")
        ->capture_default_str();
    cmd->add_option("--sweep-csv", options->sweep_csv,
                    "With --sweep-error or --sweep-realtime: also write the table as CSV (one row per "
                    "ratio, or per variant and frame count, and OUT_equal.csv: per variant at equal cost)");
    cmd->add_flag("--compare-reference", options->compare_reference,
                  "Also render the reference and write error statistics (rel_err_mean, "
                  "rel_err_p99, frac_over_error, max_err; implied by --mode error)");
}

// The image: size, camera, exposure and the files written.
void add_image_flags(CLI::App* cmd, RenderOptions* options) {
    cmd->add_option("--size", options->size, "Image size WxH")->capture_default_str();
    auto* camera =
        cmd->add_option("--camera", options->camera, "Camera ex,ey,ez,tx,ty,tz,fovy (fovy in degrees)");
    cmd->add_option("--camera-index", options->camera_index, "Camera of the file to use")->excludes(camera);
    cmd->add_option("--exposure", options->exposure,
                    "Linear exposure before the tone curve (default: automatic, the log-average "
                    "luminance of the lit pixels maps to 0.18)");
    cmd->add_option("-o,--output", options->output,
                    "Image to write: .png (8-bit, tone-mapped) or .exr (OpenEXR, linear radiance)")
        ->required();
    cmd->add_option("--float", options->float_output, "Linear image to write besides: .pfm or .exr");
    cmd->add_flag("--exr-half", options->exr_half, "Write .exr images in half floats (float by default)");
    cmd->add_option("--stats", options->stats, "Statistics JSON to write");
}

// Eye rays per pixel, strides, and the real-time mode's frames.
void add_sampling_flags(CLI::App* cmd, RenderOptions* options) {
    cmd->add_option("--spp", options->spp,
                    "Eye rays per pixel, jittered (seeded) and averaged into the pixel")
        ->check(CLI::Range(1u, 1024u))
        ->capture_default_str();
    cmd->add_option("--spp-method", options->spp_method,
                    "How --spp shades its eye rays: gpu (a whole frame per eye ray), lightcuts "
                    "(a CPU lightcut per eye ray) or reconstruction (the paper's reconstruction "
                    "cuts: CPU lightcuts at sparse samples, interpolated between)")
        ->transform(checked_names(kSppMethodNames))
        ->default_str(spp_method_name(options->spp_method));
    cmd->add_option("--spp-seed", options->spp_seed, "Seed of the eye rays' jitter")->capture_default_str();
    cmd->add_option("--threads", options->threads, "CPU workers of the CPU --spp methods")
        ->check(CLI::Range(1u, 256u))
        ->capture_default_str();
    cmd->add_option("--pixel-stride", options->pixel_stride,
                    "Reference mode: render every K-th pixel in x and y only (the same work per "
                    "pixel; K must divide both sides): a (W/K)x(H/K) image in a K^2-th of the time")
        ->check(CLI::Range(1u, 64u))
        ->capture_default_str();
    cmd->add_option("--tile-stride", options->tile_stride,
                    "Reference mode: render every K-th 8x8 tile in x and y only, the middle one "
                    "of each KxK block of tiles (neighbouring pixels stay neighbours, as in the "
                    "full frame; 8K must divide both sides): a (W/K)x(H/K) image of the tiles in "
                    "a K^2-th of the time")
        ->check(CLI::Range(1u, 64u))
        ->capture_default_str();
    cmd->add_option("--reconstruction", options->reconstruction,
                    "Lightcuts by reconstruction cuts on the GPU: full lightcuts at the corners of "
                    "BLOCKxBLOCK pixel blocks, the pixels between shaded from them with shadow rays "
                    "only where their visibility disagrees; off (or 0): a lightcut per pixel; auto: "
                    "4 for one lightcuts frame of the bound walk search at --error >= 0.01, else off")
        ->capture_default_str();
    cmd->add_option("--reconstruction-cap", options->reconstruction_cap,
                    "Reconstruction cuts: cut nodes a sample records at most (4 bytes each); a "
                    "sample over it makes its blocks' pixels run lightcuts of their own")
        ->check(CLI::Range(1u, kMaxGpuCut))
        ->capture_default_str();
    cmd->add_option("--frames", options->frames,
                    "Real-time mode: frames of the still view whose mean is the image")
        ->capture_default_str();
    add_restir_options(cmd, &options->restir);
    cmd->add_option("--realtime-filter", options->realtime_filter,
                    "Real-time mode: the edge-aware spatial filter over the first 16 frames (off: the "
                    "plain mean of the frames, as the convergence benchmark measures it)")
        ->capture_default_str();
}

}  // namespace

void add_render_flags(CLI::App& cmd, RenderOptions& options) {
    add_mode_flags(&cmd, &options);
    add_measurement_flags(&cmd, &options);
    add_image_flags(&cmd, &options);
    add_sampling_flags(&cmd, &options);
}

}  // namespace lc::client
