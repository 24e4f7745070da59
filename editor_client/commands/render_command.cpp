// editor_client render SCENE [--tree TREE.lcut | --server HOST:PORT | --spawn-server] [--builder B]
//   [--seed N] [--mode reference|lightcuts|cuts|cutsize|error] [--criterion bound|radius]
//   [--error E] [--max-cut K] [--bound-search walk|heap] [--share-cuts]
//   [--reconstruction auto|off|BLOCK [--reconstruction-cap N]]
//   [--representatives tree|pixel|importance [--representative-seed S]] [--shadows auto|on|off]
//   [--indirect on|off|vpl|radiosity]
//   [--compare-reference] [--size WxH] [--camera ex,ey,ez,tx,ty,tz,fovy | --camera-index I]
//   [--exposure E] -o OUT.png|OUT.exr [--float OUT.pfm|OUT.exr] [--exr-half] [--stats OUT.json] [--validation]
//   [--sweep-error E1,E2,... [--sweep-blocks B1,B2,...] | --mode realtime --sweep-realtime K1,K2,... [--sweep-frames F1,F2,...]]
//   [--sweep-csv OUT.csv]
//   [--spp N [--spp-method gpu|lightcuts|reconstruction] [--spp-seed S] [--threads T]]
//   [--pixel-stride K | --tile-stride K] [--realtime-cut K] [--frames N] [--realtime-filter on|off]
// Renders one frame headless on Vulkan and writes the 8-bit image (or, to an
// .exr, the linear one), optionally the linear float image and the statistics. With a tree source the default is
// lightcuts with the bound criterion; without one, the reference. `error` (and
// --compare-reference) also renders the reference and measures lightcuts
// against it (error_stats.h). Without --exposure the exposure is automatic.
// --spp shades N jittered eye rays per pixel (supersampled_render.h); the
// reference it is compared against has the same eye rays. --pixel-stride K
// renders the reference at every K-th pixel in x and y only (pixel_stride.h):
// an image of (W/K)x(H/K) in a K^2-th of the time; --tile-stride K renders
// every K-th 8x8 tile instead (strided_tiles), its pixels' neighbours those
// of the full frame, gathered into an image of the same size. --mode realtime
// is stochastic lightcuts with at most --realtime-cut shadow rays per pixel,
// its image the mean of --frames frames of the still view (realtime_frames.h).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "editor_client/commands/bake_options.h"
#include "editor_client/commands/command_errors.h"
#include "editor_client/commands/commands.h"
#include "editor_client/commands/gltf_load_flags.h"
#include "editor_client/render/analysis/environment_census.h"
#include "editor_client/render/analysis/error_stats.h"
#include "editor_client/render/sweeps/error_sweep.h"
#include "editor_client/render/sweeps/realtime_sweep.h"
#include "editor_client/render/output/exr_image.h"
#include "editor_client/render/output/image_io.h"
#include "editor_client/render/analysis/indirect_census.h"
#include "editor_client/render/pixel_stride.h"
#include "editor_client/render/realtime_frames.h"
#include "editor_client/render/render_inputs.h"
#include "editor_client/render/settings/render_settings.h"
#include "lightcuts/device/limits.h"
#include "editor_client/render/output/render_stats.h"
#include "editor_client/render/renderer.h"
#include "editor_client/render/supersampled_render.h"
#include "editor_client/report/progress_display.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/surface_geometry.h"
#include "editor_client/vk/context.h"
#include "lightcuts/gpu_layout.h"
#include "lightcuts/version.h"

namespace lc::client {
namespace {

// The side of a tile of --tile-stride: the renderer's workgroup, so a
// subgroup's pixels are the full frame's neighbours.
constexpr uint32_t kStrideTile = 8;

struct RenderOptions {
    std::string scene;
    GltfLoadOptions gltf;
    std::string tree;
    BakeFlags bake;
    std::string mode;  // empty: lightcuts with a tree source, else reference
    std::string criterion = "bound";
    float error_ratio = 0.02f;
    uint32_t max_cut = kDefaultMaxCut;
    std::string bound_search = "walk";
    bool share_cuts = false;
    std::string representatives = "tree";
    uint32_t representative_seed = 0;
    std::string shadows = "auto";
    std::string primary = "auto";
    std::string sweep_error;  // "0.005,0.01,...": print the error/time table
    std::string sweep_csv;    // and write it here
    std::string sweep_realtime;             // "8,16,32": the real-time mode's table per cut size
    std::string sweep_blocks;               // "4,8": --sweep-error's reconstruction-cut rows
    std::string sweep_frames = "1,4,16,64";  // measured after these many frames
    bool compare_reference = false;
    std::string size = "512x512";
    std::string camera;
    std::optional<int> camera_index;
    std::optional<float> exposure;  // none: automatic
    std::string output;
    std::string float_output;
    bool exr_half = false;  // .exr outputs in half, not float
    std::string stats;
    bool validation = false;
    uint32_t spp = 1;
    std::string spp_method = "gpu";
    uint64_t spp_seed = kDefaultSppSeed;
    uint32_t threads = 2;
    uint32_t pixel_stride = 1;
    uint32_t tile_stride = 1;
    uint32_t realtime_cut = 16;
    uint32_t realtime_rays = kDefaultRealtimeRays;
    std::string reconstruction = "auto";  // a block side, off, or auto (reconstruction_block_of)
    uint32_t reconstruction_cap = kDefaultReconstructionCap;
    uint32_t frames = 1;
    bool realtime_filter = true;
};

// The scene's classic lights (shaded one by one besides the tree).
std::vector<SceneLight> classic_lights_of(const Scene& scene) {
    std::vector<SceneLight> classic;
    for (const SceneLight& light : scene.lights) {
        if (light.classic) classic.push_back(light);
    }
    return classic;
}

// One frame's image and statistics: the renderer's, or the mean of --spp eye rays.
struct RenderedFrame {
    RenderStats stats;
    std::vector<float> hdr;
    std::vector<uint8_t> display;
};

// The real-time mode's frames of a still view; their mean is the image.
RenderedFrame render_realtime(Renderer& renderer, const RenderSettings& settings,
                               uint32_t frames) {
    if (Status warm = renderer.warm_up(settings); !warm) fail(warm.error());
    RenderedFrame out;
    out.stats = or_fail(render_realtime_frames(renderer, settings, frames));
    out.display = or_fail(renderer.read_display());
    out.hdr = or_fail(renderer.read_hdr());
    return out;
}

// `tiles` (not empty: a reference strided over tiles) renders those alone and
// gathers them into an image of (W/K)x(H/K), K the tiles' stride.
RenderedFrame render_frame(Renderer& renderer, const RenderSettings& settings, const SupersampleRequest* spp,
                           const WalkTree* tree, std::span<const SceneLight> classic,
                           std::span<const PixelRegion> tiles = {}, uint32_t tile_stride = 1) {
    // Timings are of the work alone, not of lavapipe compiling the shaders.
    if (Status warm = renderer.warm_up(settings); !warm) fail(warm.error());
    RenderedFrame out;
    if (!tiles.empty()) {
        out.stats = or_fail(renderer.render(settings, tiles));
        const std::vector<uint8_t> display = or_fail(renderer.read_display());
        const std::vector<float> hdr = or_fail(renderer.read_hdr());
        out.display = gather_tiles(std::span(display), settings.width, 4, tiles, tile_stride);
        out.hdr = gather_tiles(std::span(hdr), settings.width, 4, tiles, tile_stride);
        return out;
    }
    out.stats = or_fail(renderer.render(settings));
    if (spp == nullptr) {
        out.display = or_fail(renderer.read_display());
        out.hdr = or_fail(renderer.read_hdr());
        return out;
    }
    const auto start = std::chrono::steady_clock::now();
    SupersampledImage image =
        or_fail(render_supersampled(renderer, settings, *spp, tree, classic));
    // Every eye ray's frame on the wall clock, not the last one's.
    out.stats.wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    out.hdr = std::move(image.hdr);
    out.display = tone_map_image(out.hdr, settings.exposure);
    out.stats.render_ms = image.shading_ms;
    if (spp->method != SppMethod::kGpu) out.stats.render_clock = "CPU";
    out.stats.shadow_rays = image.shadow_rays;
    out.stats.nonfinite_pixels = image.nonfinite_pixels;
    out.stats.spp = spp->spp;
    out.stats.spp_method = spp_method_name(spp->method);
    out.stats.lightcuts_computed = image.cpu.lightcuts;
    out.stats.reconstruction_cuts = image.cpu.reconstruction_cuts;
    out.stats.shading_cpu_ms = image.cpu.cpu_ms;
    return out;
}

// The real-time mode's part of the summary line: per frame, over how many.
std::string realtime_summary(const RenderStats& stats) {
    if (stats.realtime_cut == 0) return "";
    char text[200];
    std::snprintf(text, sizeof text, " a frame (mean of %u), %.2f shadow rays a pixel (cut of %u, at most %u)",
                  stats.realtime_frames,
                  double(stats.shadow_rays) / double(std::max<uint64_t>(stats.geometry_pixels, 1)),
                  stats.realtime_cut, realtime_ray_budget(stats.realtime_cut, stats.realtime_rays));
    return text;
}

// GPU reconstruction cuts' part of the summary line: rays, fallbacks, storage.
std::string reconstruction_summary(const RenderStats& stats) {
    if (stats.reconstruction_block == 0) return "";
    char text[200];
    std::snprintf(text, sizeof text,
                  ", reconstruction cuts in %ux%u blocks: %.2f shadow rays a pixel, %llu pixels fell back, "
                  "%.1f MiB of records",
                  stats.reconstruction_block, stats.reconstruction_block,
                  double(stats.shadow_rays) / double(std::max<uint64_t>(stats.geometry_pixels, 1)),
                  (unsigned long long)stats.reconstruction_fallbacks,
                  double(stats.reconstruction_bytes) / (1024.0 * 1024.0));
    return text;
}

// Pixels the device's loop limit cut short, said in the summary line too.
std::string loop_limit_summary(const RenderStats& stats) {
    if (stats.loop_limit_stops == 0) return "";
    return std::to_string(stats.loop_limit_stops) + " pixels cut short by the device's loop limit, ";
}

// --tree, --server or --spawn-server: where the tree comes from, with the
// bake's progress and warnings on stderr.
TreeSource tree_source(const RenderOptions& options, const Scene& scene, ProgressDisplay& progress) {
    TreeSource source;
    source.dump = options.tree;
    if (options.bake.has_server()) {
        BakeClientOptions bake = options.bake.to_options(scene);
        bake.keep_result_channel = false;  // rendered from the decoded tree only
        bake.on_progress = [&](const ProgressMsg& p) { progress.update(p.stage, p.percent); };
        bake.on_warning = [&](const std::string& w) {
            progress.finish();
            std::cerr << "server warning: " << w << "\n";
        };
        source.bake = bake;
    }
    return source;
}

// What the command line asks for, checked: the frame's settings and how the
// written image is made from it.
struct RenderRequest {
    RenderSettings settings;
    bool error_mode = false;  // `error`: lightcuts shown as its error against the reference
    bool compare = false;     // also render the reference and measure the error
    std::vector<float> sweep_ratios;
    std::vector<uint32_t> sweep_cuts;  // --sweep-realtime
    std::vector<uint32_t> sweep_blocks;  // --sweep-blocks
    std::vector<uint32_t> sweep_frames;
    uint32_t width = 0;  // the written image's size (a stride's is smaller than the frame's)
    uint32_t height = 0;
    std::vector<PixelRegion> tiles;  // --tile-stride: the tiles rendered
};

// --reconstruction: a block side, off, or auto: 4x4 blocks wherever they
// were measured faster at equal error (docs/bench/recon2.md: the furnished
// rooms with point or mixed lights at E = 0.02; not at E = 0.005, where the
// interpolation's error exceeds the per-pixel cut's), i.e. one lightcuts
// frame of the bound criterion's walk search at E >= 0.01, every pixel.
uint32_t reconstruction_block_of(const RenderOptions& options, const RenderSettings& settings) {
    constexpr uint32_t kAutoBlock = 4;
    constexpr float kAutoMinError = 0.01f;
    if (options.reconstruction == "off") return 0;
    if (options.reconstruction == "auto") {
        const bool wins = settings.mode == RenderMode::kLightcuts && settings.criterion == CutCriterion::kBound &&
                          settings.bound_search == BoundSearch::kWalk && !settings.share_cuts &&
                          settings.error_ratio >= kAutoMinError && options.spp <= 1 &&
                          options.spp_method == "gpu" && options.pixel_stride <= 1 && options.tile_stride <= 1;
        return wins ? kAutoBlock : 0;
    }
    uint32_t block = 0;
    const std::string& text = options.reconstruction;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), block);
    if (ec != std::errc() || end != text.data() + text.size())
        fail("--reconstruction '" + text + "' is not a block side, off or auto");
    return block;
}

// The renderer's settings from the flags, in the order the flags are checked.
RenderSettings parse_settings(const RenderOptions& options, const Scene& scene, bool has_tree_source,
                              bool& error_mode) {
    RenderSettings settings;
    const std::string mode_text =
        options.mode.empty() ? (has_tree_source ? "lightcuts" : "reference") : options.mode;
    error_mode = mode_text == "error";
    std::optional<RenderMode> mode = parse_render_mode(error_mode ? "lightcuts" : mode_text);
    std::optional<CutCriterion> criterion = parse_criterion(options.criterion);
    if (!mode)
        fail("unknown --mode '" + mode_text + "' (reference, lightcuts, cuts, cutsize, realtime, error)");
    if (!criterion) fail("unknown --criterion '" + options.criterion + "' (bound, radius)");
    settings.mode = *mode;
    settings.criterion = *criterion;
    settings.error_ratio = options.error_ratio;
    settings.max_cut = options.max_cut;
    std::optional<BoundSearch> search = parse_bound_search(options.bound_search);
    if (!search) fail("unknown --bound-search '" + options.bound_search + "' (walk, heap)");
    settings.bound_search = *search;
    settings.share_cuts = options.share_cuts;
    std::optional<Representatives> representatives = parse_representatives(options.representatives);
    if (!representatives)
        fail("unknown --representatives '" + options.representatives + "' (tree, pixel, importance)");
    settings.representatives = *representatives;
    settings.representative_seed = options.representative_seed;
    settings.realtime_cut = options.realtime_cut;
    settings.realtime_rays = options.realtime_rays;
    settings.reconstruction_block = reconstruction_block_of(options, settings);
    settings.reconstruction_cap = options.reconstruction_cap;
    if (options.frames != 1 && settings.mode != RenderMode::kRealtime)
        fail("--frames accumulates the real-time mode (--mode realtime)");
    const auto [width, height] = or_fail(parse_size(options.size));
    settings.width = width;
    settings.height = height;
    settings.exposure = options.exposure.value_or(1.0f);
    settings.camera =
        or_fail(choose_camera(scene, options.camera, options.camera_index, float(width) / float(height)));
    if (Status valid = validate(settings, {.has_tree = has_tree_source}); !valid) fail(valid.error());
    return settings;
}

// The sweep, the comparison and the strides, each only where it applies.
void check_request(const RenderOptions& options, RenderRequest& request) {
    const RenderMode mode = request.settings.mode;
    request.compare = request.error_mode || options.compare_reference;
    if (!options.sweep_error.empty()) {
        request.sweep_ratios = or_fail(parse_error_list(options.sweep_error));
        if (mode == RenderMode::kReference) fail("--sweep-error needs a lightcuts mode and a tree source");
    }
    if (!options.sweep_blocks.empty()) {
        if (options.sweep_error.empty()) fail("--sweep-blocks needs --sweep-error");
        request.sweep_blocks =
            or_fail(parse_count_list(options.sweep_blocks, "--sweep-blocks", 2, kMaxReconstructionBlock));
    }
    if (!options.sweep_realtime.empty()) {
        if (mode != RenderMode::kRealtime) fail("--sweep-realtime needs --mode realtime and a tree source");
        request.sweep_cuts = or_fail(parse_count_list(options.sweep_realtime, "--sweep-realtime", 1, kMaxStochasticCut));
        request.sweep_frames = or_fail(parse_count_list(options.sweep_frames, "--sweep-frames", 1, 4096));
    }
    if (!options.sweep_csv.empty() && request.sweep_ratios.empty() && request.sweep_cuts.empty())
        fail("--sweep-csv needs --sweep-error or --sweep-realtime");
    if (request.compare && !mode_needs_tree(mode))
        fail("--compare-reference needs a lightcuts mode (lightcuts, cuts, cutsize, realtime or error)");
    if (!request.sweep_ratios.empty() && mode == RenderMode::kRealtime)
        fail("--sweep-error sweeps the deterministic lightcuts modes, not realtime");
    if (options.pixel_stride > 1 || options.tile_stride > 1) {
        if (mode != RenderMode::kReference || options.spp > 1 || options.spp_method != "gpu")
            fail("--pixel-stride and --tile-stride render the reference alone (--mode reference, no --spp)");
        if (options.pixel_stride > 1 && options.tile_stride > 1)
            fail("--pixel-stride or --tile-stride, not both");
    }
}

// --pixel-stride renders a smaller frame; --tile-stride renders some tiles of the full one.
void apply_strides(const RenderOptions& options, RenderRequest& request) {
    request.width = request.settings.width;
    request.height = request.settings.height;
    if (options.pixel_stride > 1) {
        request.settings = or_fail(strided_settings(request.settings, options.pixel_stride));
        request.width = request.settings.width;
        request.height = request.settings.height;
    }
    if (options.tile_stride > 1) {
        request.tiles =
            or_fail(strided_tiles(request.width, request.height, kStrideTile, options.tile_stride));
        request.width /= options.tile_stride;
        request.height /= options.tile_stride;
    }
}

RenderRequest make_request(const RenderOptions& options, const Scene& scene, bool has_tree_source) {
    RenderRequest request;
    request.settings = parse_settings(options, scene, has_tree_source, request.error_mode);
    check_request(options, request);
    apply_strides(options, request);
    return request;
}

// The renderer over the scene and its tree, with the environment shown
// behind it; every effect decision is logged. Returns the environment's
// decision (none without one), which the stats list besides the renderer's.
std::optional<EffectDecision> prepare_renderer(Renderer& renderer, const RenderOptions& options,
                                               const Scene& scene, const TreeSource& source,
                                               const WalkTree* tree) {
    std::vector<EffectDecision> decisions = renderer.effects().decisions;
    std::optional<EffectDecision> sky_decision;
    // A bake loaded it already; a tree from a dump was baked with it.
    const std::shared_ptr<const Environment> environment =
        source.bake ? source.bake->environment : or_fail(options.bake.environment.load(scene.environment));
    if (Status shown = renderer.set_environment(environment); !shown) fail(shown.error());
    if (environment) {
        size_t scene_directional_lights = 0;
        for (const SceneLight& light : scene.lights)
            scene_directional_lights += !light.classic && light.type == LightType::kDirectional;
        sky_decision = environment_decision(*environment, tree, scene_directional_lights);
        decisions.push_back(*sky_decision);
    }
    for (const EffectDecision& d : decisions)
        spdlog::info("effect: {}: {}, {}", d.name, d.simulated ? "simulated" : "skipped", d.reason);
    return sky_decision;
}

std::unique_ptr<Renderer> create_renderer(const vk::Context& context, const RenderOptions& options,
                                          const Scene& scene, const WalkTree* tree) {
    RendererOptions renderer_options;
    renderer_options.shadows = or_fail(parse_shadow_mode(options.shadows));
    renderer_options.indirect = options.bake.renders_indirect();
    const std::optional<PrimaryChoice> primary = parse_primary_choice(options.primary);
    if (!primary) fail("--primary " + options.primary + ": expected auto, raster or rays");
    renderer_options.primary = *primary;
    // A sweep measures the estimator: the plain mean of the frames.
    if (!options.realtime_filter || !options.sweep_realtime.empty()) renderer_options.realtime.filter_frames = 0;
    return or_fail(Renderer::create(context, scene, tree, renderer_options));
}

// --sweep-error: the price of accuracy, printed (and written as CSV).
void print_sweep(Renderer& renderer, const RenderOptions& options, const RenderRequest& request) {
    const RenderSettings& settings = request.settings;
    ErrorSweep sweep = or_fail(run_error_sweep(renderer, settings, request.sweep_ratios, request.sweep_blocks));
    std::string how = criterion_name(settings.criterion) + std::string(" criterion");
    if (settings.criterion == CutCriterion::kBound)
        how += std::string(", ") + bound_search_name(settings.bound_search) + " search";
    std::printf("error sweep, %s, max cut %u, %ux%u:\n", how.c_str(), settings.max_cut, request.width,
                request.height);
    print_error_sweep(stdout, sweep);
    if (!options.sweep_csv.empty()) {
        if (Status written = write_error_sweep_csv(options.sweep_csv, sweep); !written) fail(written.error());
    }
}

// --sweep-realtime: the real-time mode's price of accuracy, printed (and written as CSV).
void print_realtime_sweep_of(Renderer& renderer, const RenderOptions& options, const RenderRequest& request) {
    RealtimeSweep sweep =
        or_fail(run_realtime_sweep(renderer, request.settings, request.sweep_cuts, request.sweep_frames));
    const uint32_t rays = request.settings.realtime_rays;
    const std::string budget = rays == 0 ? "a shadow ray per cut node" : std::to_string(rays) + " shadow rays a pixel";
    std::printf("real-time sweep, %s, %ux%u:\n", budget.c_str(), request.width, request.height);
    print_realtime_sweep(stdout, sweep);
    if (!options.sweep_csv.empty()) {
        if (Status written = write_realtime_sweep_csv(options.sweep_csv, sweep); !written) fail(written.error());
    }
}

// --spp and --spp-method, checked against the mode; null: one eye ray per pixel on the GPU.
std::optional<SupersampleRequest> supersample_request(const RenderOptions& options,
                                                      const RenderRequest& request) {
    if (options.spp <= 1 && options.spp_method == "gpu") return std::nullopt;
    SupersampleRequest spp;
    spp.spp = options.spp;
    spp.seed = options.spp_seed;
    spp.threads = options.threads;
    std::optional<SppMethod> method = parse_spp_method(options.spp_method);
    if (!method) fail("unknown --spp-method '" + options.spp_method + "'");
    spp.method = *method;
    const RenderSettings& settings = request.settings;
    if (!mode_is_shaded(settings.mode) || request.error_mode || !request.sweep_ratios.empty())
        fail("--spp renders the lightcuts or reference mode (no cut views, error or sweep)");
    if (spp.method != SppMethod::kGpu && settings.mode != RenderMode::kLightcuts)
        fail("--spp-method " + options.spp_method + " shades lightcuts (--mode lightcuts)");
    if (spp.method != SppMethod::kGpu && settings.representatives != Representatives::kTree)
        fail("--spp-method " + options.spp_method + " shades with the tree's representatives");
    return spp;
}

// The command's image: the frame (the mean of the real-time mode's frames,
// or of --spp eye rays), its size and stride in the stats, tone-mapped at the
// automatic exposure where the flags leave it to the command.
RenderedFrame render_image(Renderer& renderer, const RenderOptions& options, const RenderRequest& request,
                           const SupersampleRequest* spp, const WalkTree* tree,
                           std::span<const SceneLight> classic) {
    const RenderSettings& settings = request.settings;
    RenderedFrame rendered =
        settings.mode == RenderMode::kRealtime
            ? render_realtime(renderer, settings, options.frames)
            : render_frame(renderer, settings, spp, tree, classic, request.tiles, options.tile_stride);
    RenderStats& stats = rendered.stats;
    stats.pixel_stride = std::max(options.pixel_stride, options.tile_stride);
    if (options.tile_stride > 1) stats.stride_tile = kStrideTile;
    stats.width = request.width;
    stats.height = request.height;
    stats.exposure = settings.exposure;
    return rendered;
}

// Shaded modes without --exposure: the read-back tone-mapped at the automatic exposure.
void apply_auto_exposure(const RenderOptions& options, const RenderRequest& request, RenderedFrame& image) {
    const bool shaded = mode_is_shaded(request.settings.mode) && !request.error_mode;
    if (!shaded || options.exposure) return;
    image.stats.exposure = auto_exposure(image.hdr);
    image.stats.auto_exposure = true;
    image.display = tone_map_image(image.hdr, float(image.stats.exposure));
}

// --compare-reference and --mode error: the reference with the same eye rays,
// the error statistics, and for `error` the heatmap as the image.
void compare_with_reference(Renderer& renderer, const RenderRequest& request, const SupersampleRequest* spp,
                            const WalkTree* tree, std::span<const SceneLight> classic, RenderedFrame& image) {
    RenderSettings reference_settings = request.settings;
    reference_settings.mode = RenderMode::kReference;
    std::optional<SupersampleRequest> reference_spp;
    if (spp != nullptr) {
        reference_spp = *spp;
        reference_spp->method = SppMethod::kGpu;
    }
    RenderedFrame reference =
        render_frame(renderer, reference_settings, reference_spp ? &*reference_spp : nullptr, tree, classic);
    const float error_ratio = request.settings.error_ratio;
    ErrorStats errors =
        or_fail(compute_error_stats(image.hdr, reference.hdr, request.width, request.height, error_ratio));
    RenderStats& stats = image.stats;
    stats.has_error_stats = true;
    stats.rel_err_mean = errors.rel_err_mean;
    stats.rel_err_p99 = errors.rel_err_p99;
    stats.frac_over_error = errors.frac_over_error;
    stats.frac_over_2pct = fraction_over(errors, 0.02);
    stats.max_err = errors.max_err;
    stats.error_pixels = errors.measured_pixels;
    stats.reference_ms = reference.stats.render_ms;
    stats.reference_shadow_rays = reference.stats.shadow_rays;
    if (request.error_mode) {
        image.display = error_heatmap(errors, reference.hdr, request.width, request.height, error_ratio);
        stats.mode = "error";
    }
}

// The linear image: the RGB of the RGBA read-back.
FloatImage linear_image(const RenderRequest& request, const std::vector<float>& hdr) {
    FloatImage image;
    image.width = request.width;
    image.height = request.height;
    image.rgb.reserve(size_t(request.width) * request.height * 3);
    for (size_t i = 0; i < hdr.size(); i += 4) image.rgb.insert(image.rgb.end(), {hdr[i], hdr[i + 1], hdr[i + 2]});
    return image;
}

// An EXR's header says what made it: the program, the mode, the scene and the tone map's exposure.
ExrWriteOptions exr_options(const RenderOptions& options, const RenderStats& stats) {
    ExrWriteOptions exr;
    exr.pixels = options.exr_half ? ExrPixels::kHalf : ExrPixels::kFloat;
    exr.attributes = {{"software", std::string("editor_client ") + kVersion},
                      {"lightcuts.mode", stats.mode},
                      {"lightcuts.scene", options.scene},
                      {"lightcuts.lights", std::to_string(stats.lights)},
                      {"lightcuts.nodes", std::to_string(stats.nodes)},
                      {"lightcuts.exposure", std::to_string(stats.exposure)}};
    return exr;
}

// The linear image as the path's extension says: OpenEXR (.exr) or PFM.
void write_linear(const std::string& path, const FloatImage& image, const RenderOptions& options,
                  const RenderStats& stats) {
    Status written = is_exr_path(path) ? write_exr(path, image, exr_options(options, stats)) : write_pfm(path, image);
    if (!written) fail(written.error());
}

// -o and --float: the 8-bit image (an .exr -o: the linear one) and the linear one.
void write_images(const RenderOptions& options, const RenderRequest& request, const RenderedFrame& image) {
    if (is_exr_path(options.output)) {
        write_linear(options.output, linear_image(request, image.hdr), options, image.stats);
    } else {
        Status png = write_png(options.output, request.width, request.height, image.display);
        if (!png) fail(png.error());
    }
    if (!options.float_output.empty())
        write_linear(options.float_output, linear_image(request, image.hdr), options, image.stats);
}

// The imported tree as the renderer and the CPU evaluator both walk it, and
// the one fact of the imported form the walk form does not keep.
struct RenderTree {
    std::optional<WalkTree> walk;  // none without a tree source
    uint32_t deepest_vpl_bounce = 0;

    const WalkTree* get() const { return walk ? &*walk : nullptr; }
};

// Converts the imported tree (null: none) once and lets it go: the command
// keeps one node array.
RenderTree walk_tree_of(std::shared_ptr<const LightTree> imported) {
    RenderTree tree;
    if (!imported) return tree;
    Result<WalkTree> walk = make_walk_tree(*imported);
    if (!walk) fail("light tree: " + walk.error());
    tree.walk = std::move(walk).value();
    tree.deepest_vpl_bounce = deepest_vpl_bounce(*imported);
    return tree;
}

// What the tree's indirect light is, or why there is none, in a line.
void print_indirect_census(const RenderStats& stats, const Scene& scene, const TreeSource& source,
                           const RenderTree& tree) {
    IndirectCensusFacts indirect_facts;
    indirect_facts.has_tree = tree.walk.has_value();
    indirect_facts.vpls = stats.indirect_lights - stats.indirect_patches;
    indirect_facts.patches = stats.indirect_patches;
    // Only a tree with VPLs has a bounce to name.
    if (tree.walk && indirect_facts.vpls > 0) indirect_facts.deepest_vpl_bounce = tree.deepest_vpl_bounce;
    indirect_facts.left_out = stats.indirect == "off";
    indirect_facts.clamped_fraction = stats.clamped_fraction();
    if (source.bake) indirect_facts.baked = source.bake->indirect;
    // Only a bake that made no indirect light needs to know why.
    if (source.bake && stats.indirect_lights == 0)
        indirect_facts.scene_has_geometry = !extract_surface_geometry(scene).triangles.empty();
    if (std::string census = indirect_census(indirect_facts); !census.empty())
        std::printf("indirect: %s\n", census.c_str());
}

// The loop limit's and the heap's shortfalls, the error against the reference, and the summary line.
void print_report(const RenderStats& stats, const RenderOptions& options, const RenderRequest& request,
                  double command_ms) {
    if (stats.heap_capacity > 0 && stats.heap_capacity < stats.max_cut_setting)
        std::printf(
            "heap search: %u entries on this device (its driver refused private memory for "
            "max cut %u); %llu pixels filled the heap\n",
            stats.heap_capacity, stats.max_cut_setting, (unsigned long long)stats.max_cut_hits);
    if (stats.primary == "rays") std::printf("G-buffer: primary rays in compute (%.2f ms GPU)\n", stats.gbuffer_ms);
    if (stats.has_error_stats)
        std::printf(
            "error vs reference (%.0f ms GPU): mean %.4f, p99 %.4f, %.4f of %llu pixels "
            "over %.3f, max %.4f, %llu max-cut hits\n",
            stats.reference_ms, stats.rel_err_mean, stats.rel_err_p99, stats.frac_over_error,
            (unsigned long long)stats.error_pixels, request.settings.error_ratio, stats.max_err,
            (unsigned long long)stats.max_cut_hits);
    std::printf(
        "%s: %s %ux%u, %llu lights (%llu in the tree, %llu classic), %llu nodes, render %.2f ms "
        "%s%s, %.2f ms wall (%.0f ms total), avg cut %.2f, max cut %u, %llu non-finite pixels, "
        "%s%u validation messages -> %s\n",
        stats.device.c_str(), stats.mode.c_str(), request.width, request.height,
        (unsigned long long)stats.lights, (unsigned long long)stats.tree_lights,
        (unsigned long long)stats.classic_lights, (unsigned long long)stats.nodes, stats.render_ms,
        stats.render_clock.c_str(), (realtime_summary(stats) + reconstruction_summary(stats)).c_str(), stats.wall_ms, command_ms, stats.avg_cut,
        stats.max_cut, (unsigned long long)stats.nonfinite_pixels, loop_limit_summary(stats).c_str(),
        stats.validation_messages, options.output.c_str());
}

void run_render(const RenderOptions& options) {
    const auto command_start = std::chrono::steady_clock::now();
    if (options.exr_half && !is_exr_path(options.output) && !is_exr_path(options.float_output))
        fail("--exr-half needs an .exr image to write (-o IMAGE.exr or --float IMAGE.exr)");
    std::vector<std::string> warnings;
    Scene scene = or_fail(load_scene(options.scene, warnings, options.gltf));
    for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
    ProgressDisplay progress(stderr);
    const TreeSource source = tree_source(options, scene, progress);
    const RenderRequest request = make_request(options, scene, !source.empty());
    const RenderTree tree = walk_tree_of(or_fail(obtain_tree(scene, source)));
    progress.finish();

    vk::ContextOptions context_options;
    context_options.validation = options.validation;
    vk::Context context = or_fail(vk::Context::create(context_options));
    std::unique_ptr<Renderer> renderer = create_renderer(context, options, scene, tree.get());
    const std::optional<EffectDecision> sky_decision =
        prepare_renderer(*renderer, options, scene, source, tree.get());
    if (!request.sweep_ratios.empty()) print_sweep(*renderer, options, request);
    if (!request.sweep_cuts.empty()) print_realtime_sweep_of(*renderer, options, request);
    const std::optional<SupersampleRequest> spp = supersample_request(options, request);
    const SupersampleRequest* eye_rays = spp ? &*spp : nullptr;
    const std::vector<SceneLight> classic = classic_lights_of(scene);
    RenderedFrame image = render_image(*renderer, options, request, eye_rays, tree.get(), classic);
    if (sky_decision)
        (sky_decision->simulated ? image.stats.effects_simulated : image.stats.effects_skipped)
            .push_back(*sky_decision);
    apply_auto_exposure(options, request, image);
    if (request.compare) compare_with_reference(*renderer, request, eye_rays, tree.get(), classic, image);
    write_images(options, request, image);

    RenderStats& stats = image.stats;
    stats.scene = options.scene;
    stats.validation_messages = context.validation_message_count();
    const double command_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - command_start).count();
    if (!options.stats.empty()) {
        if (Status written = write_stats_json(options.stats, stats); !written) fail(written.error());
    }
    if (stats.loop_limit_stops > 0)
        std::fprintf(stderr,
                     "warning: the device's loop limit cut %llu pixels' cut search short; they "
                     "keep their last complete pass (counted in loop_limit_stops)\n",
                     (unsigned long long)stats.loop_limit_stops);
    print_indirect_census(stats, scene, source, tree);
    print_report(stats, options, request, command_ms);
}

// --mode and the cut: criterion, error, search, representatives, shadows.
void add_mode_flags(CLI::App* cmd, RenderOptions* options) {
    cmd->add_option("--mode", options->mode,
                    "reference, lightcuts, cuts, cutsize, realtime (stochastic lightcuts with a "
                    "fixed shadow-ray budget) or error (relative error of lightcuts "
                    "against the reference, as a heatmap; 0 .. 2 x --error). Default: lightcuts "
                    "when a tree source (--tree, --server, --spawn-server) is given, else "
                    "reference")
        ->check(CLI::IsMember({"reference", "lightcuts", "cuts", "cutsize", "realtime", "error"}));
    cmd->add_option("--criterion", options->criterion,
                    "Cut criterion: bound (the paper's error bounds) or radius (the thesis)")
        ->check(CLI::IsMember({"radius", "bound"}))
        ->capture_default_str();
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
        ->check(CLI::IsMember({"walk", "heap"}))
        ->capture_default_str();
    cmd->add_flag("--share-cuts", options->share_cuts,
                  "Bound criterion, walk search: one cut per subgroup of neighbouring pixels "
                  "(8 on lavapipe), refined until it meets every one of their bounds");
    cmd->add_option("--representatives", options->representatives,
                    "Bound criterion: evaluate a cluster through the tree's representative (drawn "
                    "once for the image), one drawn per pixel with the same probabilities "
                    "(errors independent between pixels), or one drawn per pixel in proportion "
                    "to intensity x a bound of cos / d^2 at the point (importance; walk search)")
        ->check(CLI::IsMember({"tree", "pixel", "importance"}))
        ->capture_default_str();
    cmd->add_option("--representative-seed", options->representative_seed,
                    "--representatives pixel or importance: the seed of the per-pixel draws")
        ->capture_default_str();
    cmd->add_option("--shadows", options->shadows,
                    "Shadow rays: auto (simulated when a surface may hide a light; the stats "
                    "JSON says why), on or off")
        ->check(CLI::IsMember({"auto", "on", "off"}))
        ->capture_default_str();
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
                    "With --mode realtime: print the real-time mode's price of accuracy on this "
                    "scene and camera: for each cut size of the list (e.g. 8,16,32) the still "
                    "view's frames accumulated, against one reference, after each count of "
                    "--sweep-frames: GPU time, shadow rays and measured error");
    cmd->add_option("--sweep-frames", options->sweep_frames,
                    "With --sweep-realtime: the frame counts measured, ascending")
        ->capture_default_str();
    cmd->add_option("--sweep-csv", options->sweep_csv,
                    "With --sweep-error or --sweep-realtime: also write the table as CSV (one row per "
                    "ratio, or per cut size and frame count)");
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
        ->check(CLI::IsMember({"gpu", "lightcuts", "reconstruction"}))
        ->capture_default_str();
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
    cmd->add_option("--realtime-cut", options->realtime_cut,
                    "Real-time mode: nodes of each 8x8 block's cut, 1 to 32 (at most this many "
                    "shadow rays per pixel and frame)")
        ->capture_default_str();
    cmd->add_option("--realtime-rays", options->realtime_rays,
                    "Real-time mode: shadow rays per pixel and frame, picked among the cut's "
                    "drawn lights by their unshadowed light (unbiased); 0 traces one per cut node")
        ->check(CLI::Range(0u, kMaxStochasticRays))
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
    cmd->add_option("--realtime-filter", options->realtime_filter,
                    "Real-time mode: the edge-aware spatial filter over the first 16 frames (off: the "
                    "plain mean of the frames, as the convergence benchmark measures it)")
        ->capture_default_str();
    cmd->add_option("--primary", options->primary,
                    "How the G-buffer is made: raster, rays (a compute pass: faster on GPUs that "
                    "rasterise on few units; untextured scenes), or auto (rays on a GPU for a scene "
                    "without textures, raster otherwise)")
        ->capture_default_str();
}

}  // namespace

void register_render_command(CLI::App& app) {
    auto options = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene headless with Vulkan");
    cmd->add_option("scene", options->scene, "glTF 2.0 scene (.gltf/.glb) with KHR_lights_punctual")
        ->required();
    add_gltf_load_flags(*cmd, options->gltf);
    auto* tree = cmd->add_option("--tree", options->tree, "Light tree: a result channel dump (bake -o)");
    options->bake.add_to(*cmd, /*server_required=*/false, /*renders=*/true);
    tree->excludes(cmd->get_option("--server"))->excludes(cmd->get_option("--spawn-server"));
    add_mode_flags(cmd, options.get());
    add_measurement_flags(cmd, options.get());
    add_image_flags(cmd, options.get());
    add_sampling_flags(cmd, options.get());
    cmd->add_flag("--validation", options->validation,
                  "Enable the Vulkan validation layer (also LC_VALIDATION=1)");
    cmd->callback([options] { run_render(*options); });
}

}  // namespace lc::client
