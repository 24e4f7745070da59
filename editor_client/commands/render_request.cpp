#include "editor_client/commands/render_request.h"

#include <charconv>
#include <string>

#include "editor_client/commands/command_errors.h"
#include "editor_client/render/render_inputs.h"
#include "editor_client/render/sweeps/error_sweep.h"
#include "editor_client/render/sweeps/realtime_sweep.h"
#include "lightcuts/device/limits.h"

namespace lc::client {
namespace {

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
                          options.spp_method == SppMethod::kGpu && options.pixel_stride <= 1 &&
                          options.tile_stride <= 1;
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
RenderSettings parse_settings(const RenderOptions& options, const Scene& scene, bool has_tree_source) {
    RenderSettings settings;
    settings.mode = options.mode.value_or(has_tree_source ? RenderMode::kLightcuts : RenderMode::kReference);
    settings.criterion = options.criterion;
    settings.error_ratio = options.error_ratio;
    settings.max_cut = options.max_cut;
    settings.bound_search = options.bound_search;
    settings.share_cuts = options.share_cuts;
    settings.representatives = options.shared.representatives;
    settings.representative_seed = options.representative_seed;
    settings.realtime_cut = options.shared.realtime_cut;
    settings.realtime_rays = options.shared.realtime_rays;
    settings.reconstruction_block = reconstruction_block_of(options, settings);
    settings.reconstruction_cap = options.reconstruction_cap;
    settings.restir = or_fail(restir_settings_from(options.restir));
    if (options.frames != 1 && !mode_accumulates(settings.mode))
        fail("--frames accumulates the real-time modes (--mode realtime or restir)");
    const auto [width, height] = or_fail(parse_size(options.size));
    settings.width = width;
    settings.height = height;
    settings.exposure = options.exposure.value_or(1.0f);
    settings.camera =
        or_fail(choose_camera(scene, options.camera, options.camera_index, float(width) / float(height)));
    if (Status valid = validate(settings, {.has_tree = has_tree_source}); !valid) fail(valid.error());
    return settings;
}

// --sweep-realtime's variants, frame counts and path.
void check_realtime_sweep(const RenderOptions& options, RenderRequest& request) {
    if (request.settings.mode != RenderMode::kRealtime)
        fail("--sweep-realtime needs --mode realtime and a tree source");
    RealtimeSweepPlan& plan = request.realtime_sweep;
    plan.variants = or_fail(parse_realtime_variants(options.sweep_realtime, request.settings));
    plan.frame_counts = or_fail(parse_count_list(options.sweep_frames, "--sweep-frames", 1, 4096));
    if (options.sweep_path > 4096) fail("--sweep-path: " + std::to_string(options.sweep_path) + " is over 4096 frames");
    plan.path_frames = options.sweep_path;
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
    if (!options.sweep_realtime.empty()) check_realtime_sweep(options, request);
    if (!options.sweep_csv.empty() && request.sweep_ratios.empty() && request.realtime_sweep.variants.empty())
        fail("--sweep-csv needs --sweep-error or --sweep-realtime");
    if (request.compare && !mode_needs_tree(mode))
        fail("--compare-reference needs a lightcuts mode (lightcuts, cuts, cutsize, realtime or error)");
    if (!request.sweep_ratios.empty() && mode == RenderMode::kRealtime)
        fail("--sweep-error sweeps the deterministic lightcuts modes, not realtime");
    if (options.pixel_stride > 1 || options.tile_stride > 1) {
        if (mode != RenderMode::kReference || options.spp > 1 || options.spp_method != SppMethod::kGpu)
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

}  // namespace

RenderRequest make_request(const RenderOptions& options, const Scene& scene, bool has_tree_source) {
    RenderRequest request;
    request.settings = parse_settings(options, scene, has_tree_source);
    request.error_mode = options.error_view;
    check_request(options, request);
    apply_strides(options, request);
    return request;
}

std::optional<SupersampleRequest> supersample_request(const RenderOptions& options,
                                                      const RenderRequest& request) {
    if (options.spp <= 1 && options.spp_method == SppMethod::kGpu) return std::nullopt;
    SupersampleRequest spp;
    spp.spp = options.spp;
    spp.seed = options.spp_seed;
    spp.threads = options.threads;
    spp.method = options.spp_method;
    const RenderSettings& settings = request.settings;
    if (!mode_is_shaded(settings.mode) || request.error_mode || !request.sweep_ratios.empty())
        fail("--spp renders the lightcuts or reference mode (no cut views, error or sweep)");
    if (spp.method != SppMethod::kGpu && settings.mode != RenderMode::kLightcuts)
        fail(std::string("--spp-method ") + spp_method_name(spp.method) + " shades lightcuts (--mode lightcuts)");
    if (spp.method != SppMethod::kGpu && settings.representatives != Representatives::kTree)
        fail(std::string("--spp-method ") + spp_method_name(spp.method) + " shades with the tree's representatives");
    return spp;
}

}  // namespace lc::client
