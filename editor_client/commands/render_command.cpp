// editor_client render SCENE [--tree TREE.lcut | --server HOST:PORT | --spawn-server] [--builder B]
//   [--seed N] [--mode reference|lightcuts|cuts|cutsize|error] [--criterion bound|radius]
//   [--error E] [--max-cut K] [--bound-search walk|heap] [--share-cuts]
//   [--reconstruction auto|off|BLOCK [--reconstruction-cap N]]
//   [--representatives tree|pixel|importance [--representative-seed S]] [--shadows auto|on|off]
//   [--indirect on|off|vpl|radiosity]
//   [--compare-reference] [--size WxH] [--camera ex,ey,ez,tx,ty,tz,fovy | --camera-index I]
//   [--exposure E] -o OUT.png|OUT.exr [--float OUT.pfm|OUT.exr] [--exr-half] [--stats OUT.json] [--validation]
//   [--sweep-error E1,E2,... [--sweep-blocks B1,B2,...] | --mode realtime --sweep-realtime V1,V2,... [--sweep-frames F1,F2,...] [--sweep-path N]]
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
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "editor_client/commands/command_errors.h"
#include "editor_client/commands/commands.h"
#include "editor_client/commands/render_options.h"
#include "editor_client/commands/render_output.h"
#include "editor_client/commands/render_request.h"
#include "editor_client/commands/render_summary.h"
#include "editor_client/render/analysis/environment_census.h"
#include "editor_client/render/analysis/error_stats.h"
#include "editor_client/render/analysis/indirect_census.h"
#include "editor_client/render/output/exr_image.h"
#include "editor_client/render/output/image_io.h"
#include "editor_client/render/realtime_frames.h"
#include "editor_client/render/renderer.h"
#include "editor_client/render/sweeps/error_sweep.h"
#include "editor_client/render/sweeps/realtime_sweep.h"
#include "editor_client/report/progress_display.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/vk/context.h"

namespace lc::client {
namespace {

// The scene's classic lights (shaded one by one besides the tree).
std::vector<SceneLight> classic_lights_of(const Scene& scene) {
    std::vector<SceneLight> classic;
    for (const SceneLight& light : scene.lights) {
        if (light.classic) classic.push_back(light);
    }
    return classic;
}

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
    out.stats.timing.wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    out.hdr = std::move(image.hdr);
    out.display = tone_map_image(out.hdr, settings.exposure);
    out.stats.timing.render_ms = image.shading_ms;
    if (spp->method != SppMethod::kGpu) out.stats.timing.render_clock = "CPU";
    out.stats.shadows.rays = image.shadow_rays;
    out.stats.nonfinite_pixels = image.nonfinite_pixels;
    out.stats.supersampling.spp = spp->spp;
    out.stats.supersampling.method = spp_method_name(spp->method);
    out.stats.supersampling.lightcuts_computed = image.cpu.lightcuts;
    out.stats.supersampling.reconstruction_cuts = image.cpu.reconstruction_cuts;
    out.stats.supersampling.shading_cpu_ms = image.cpu.cpu_ms;
    return out;
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
    renderer_options.shadows = options.shared.shadows;
    renderer_options.indirect = options.bake.renders_indirect();
    renderer_options.primary = options.shared.primary;
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
    RealtimeSweep sweep = or_fail(run_realtime_sweep(renderer, request.settings, request.realtime_sweep));
    std::printf("real-time sweep, %zu variants, %ux%u, still and along a %u-frame orbit:\n",
                request.realtime_sweep.variants.size(), request.width, request.height,
                request.realtime_sweep.path_frames);
    print_realtime_sweep(stdout, sweep);
    if (!options.sweep_csv.empty()) {
        if (Status written = write_realtime_sweep_csv(options.sweep_csv, sweep); !written) fail(written.error());
        const std::filesystem::path summary = realtime_summary_path(options.sweep_csv);
        if (Status written = write_realtime_summary_csv(summary, sweep); !written) fail(written.error());
    }
}

// The command's image: the frame (the mean of the real-time mode's frames,
// or of --spp eye rays), its size and stride in the stats, tone-mapped at the
// automatic exposure where the flags leave it to the command.
RenderedFrame render_image(Renderer& renderer, const RenderOptions& options, const RenderRequest& request,
                           const SupersampleRequest* spp, const WalkTree* tree,
                           std::span<const SceneLight> classic) {
    const RenderSettings& settings = request.settings;
    RenderedFrame rendered =
        mode_accumulates(settings.mode)
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
    stats.error.measured = true;
    stats.error.rel_err_mean = errors.rel_err_mean;
    stats.error.rel_err_p99 = errors.rel_err_p99;
    stats.error.frac_over_error = errors.frac_over_error;
    stats.error.frac_over_2pct = fraction_over(errors, 0.02);
    stats.error.max_err = errors.max_err;
    stats.error.pixels = errors.measured_pixels;
    stats.error.reference_ms = reference.stats.timing.render_ms;
    stats.error.reference_shadow_rays = reference.stats.shadows.rays;
    if (request.error_mode) {
        image.display = error_heatmap(errors, reference.hdr, request.width, request.height, error_ratio);
        stats.mode = "error";
    }
}

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
    if (!request.realtime_sweep.variants.empty()) print_realtime_sweep_of(*renderer, options, request);
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
    if (stats.cuts.loop_limit_stops > 0)
        std::fprintf(stderr,
                     "warning: the device's loop limit cut %llu pixels' cut search short; they "
                     "keep their last complete pass (counted in loop_limit_stops)\n",
                     (unsigned long long)stats.cuts.loop_limit_stops);
    print_indirect_census(stats, scene, source, tree);
    print_report(stats, options, request, command_ms);
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
    add_render_flags(*cmd, *options);
    cmd->add_flag("--validation", options->validation,
                  "Enable the Vulkan validation layer (also LC_VALIDATION=1)");
    cmd->callback([options] { run_render(*options); });
}

}  // namespace lc::client
