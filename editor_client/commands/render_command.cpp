// editor_client render SCENE [--tree TREE.lcut | --server HOST:PORT | --spawn-server] [--builder B]
//   [--seed N] [--mode reference|lightcuts|cuts|cutsize] [--criterion radius] [--size WxH]
//   [--camera ex,ey,ez,tx,ty,tz,fovy | --camera-index I] [--exposure E] -o OUT.png
//   [--float OUT.pfm] [--stats OUT.json] [--validation]
// Renders one frame headless on Vulkan and writes the 8-bit image, optionally
// the linear float image and the statistics.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "editor_client/commands/bake_options.h"
#include "editor_client/commands/commands.h"
#include "editor_client/render/image_io.h"
#include "editor_client/render/render_inputs.h"
#include "editor_client/render/render_settings.h"
#include "editor_client/render/render_stats.h"
#include "editor_client/render/renderer.h"
#include "editor_client/report/progress_display.h"
#include "editor_client/scene/gltf_loader.h"
#include "editor_client/vk/context.h"

namespace lc::client {
namespace {

struct RenderOptions {
    std::string scene;
    std::string tree;
    BakeFlags bake;
    std::string mode = "reference";
    std::string criterion = "radius";
    std::string size = "512x512";
    std::string camera;
    std::optional<int> camera_index;
    float exposure = 1.0f;
    std::string output;
    std::string float_output;
    std::string stats;
    bool validation = false;
};

[[noreturn]] void fail(const std::string& message) {
    std::cerr << "error: " << message << "\n";
    throw CLI::RuntimeError(1);
}

template <typename T>
T or_fail(Result<T> result) {
    if (!result) fail(result.error());
    return std::move(result).value();
}

void run_render(const RenderOptions& options) {
    auto command_start = std::chrono::steady_clock::now();
    std::vector<std::string> warnings;
    Scene scene = or_fail(load_scene(options.scene, warnings));
    for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";

    RenderSettings settings;
    std::optional<RenderMode> mode = parse_render_mode(options.mode);
    std::optional<CutCriterion> criterion = parse_criterion(options.criterion);
    if (!mode) fail("unknown --mode '" + options.mode + "' (reference, lightcuts, cuts, cutsize)");
    if (!criterion) fail("unknown --criterion '" + options.criterion + "' (radius)");
    settings.mode = *mode;
    settings.criterion = *criterion;
    auto [width, height] = or_fail(parse_size(options.size));
    settings.width = width;
    settings.height = height;
    if (!std::isfinite(options.exposure) || options.exposure < 0.0f)
        fail("--exposure must be a finite number >= 0");
    settings.exposure = options.exposure;
    settings.camera = or_fail(
        choose_camera(scene, options.camera, options.camera_index, float(width) / float(height)));

    TreeSource source;
    source.dump = options.tree;
    ProgressDisplay progress(stderr);
    if (options.bake.has_server()) {
        BakeClientOptions bake = options.bake.to_options();
        bake.on_progress = [&](const ProgressMsg& p) { progress.update(p.stage, p.percent); };
        bake.on_warning = [&](const std::string& w) {
            progress.finish();
            std::cerr << "server warning: " << w << "\n";
        };
        source.bake = bake;
    }
    if (mode_needs_tree(settings.mode) && source.empty())
        fail("mode '" + options.mode +
             "' needs a light tree: give --tree TREE.lcut, --server "
             "HOST:PORT or --spawn-server");
    std::shared_ptr<const LightTree> tree = or_fail(obtain_tree(scene, source));
    progress.finish();

    vk::ContextOptions context_options;
    context_options.validation = options.validation;
    vk::Context context = or_fail(vk::Context::create(context_options));
    std::unique_ptr<Renderer> renderer = or_fail(Renderer::create(context, scene, tree.get()));
    for (const EffectDecision& d : renderer->effects().decisions)
        spdlog::info("effect: {}: {}, {}", d.name, d.simulated ? "simulated" : "skipped", d.reason);

    RenderStats stats = or_fail(renderer->render(settings));
    std::vector<uint8_t> display = or_fail(renderer->read_display());
    Status png = write_png(options.output, width, height, display);
    if (!png) fail(png.error());
    if (!options.float_output.empty()) {
        std::vector<float> hdr = or_fail(renderer->read_hdr());
        FloatImage image;
        image.width = width;
        image.height = height;
        image.rgb.reserve(size_t(width) * height * 3);
        for (size_t i = 0; i < hdr.size(); i += 4)
            image.rgb.insert(image.rgb.end(), {hdr[i], hdr[i + 1], hdr[i + 2]});
        Status pfm = write_pfm(options.float_output, image);
        if (!pfm) fail(pfm.error());
    }

    stats.scene = options.scene;
    stats.validation_messages = context.validation_message_count();
    double command_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - command_start)
            .count();
    if (!options.stats.empty()) {
        Status written = write_stats_json(options.stats, stats);
        if (!written) fail(written.error());
    }
    std::printf(
        "%s: %s %ux%u, %llu lights (%llu in the tree, %llu classic), %llu nodes, render %.2f ms "
        "GPU, %.2f ms wall (%.0f ms total), avg cut %.2f, max cut %u, %llu non-finite pixels, "
        "%u validation messages -> %s\n",
        stats.device.c_str(), stats.mode.c_str(), width, height, (unsigned long long)stats.lights,
        (unsigned long long)stats.tree_lights, (unsigned long long)stats.classic_lights,
        (unsigned long long)stats.nodes, stats.render_ms, stats.wall_ms, command_ms, stats.avg_cut,
        stats.max_cut, (unsigned long long)stats.nonfinite_pixels, stats.validation_messages,
        options.output.c_str());
}

}  // namespace

void add_render_command(CLI::App& app) {
    auto options = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene headless with Vulkan");
    cmd->add_option("scene", options->scene, "glTF 2.0 scene (.gltf/.glb) with KHR_lights_punctual")
        ->required();
    auto* tree =
        cmd->add_option("--tree", options->tree, "Light tree: a result channel dump (bake -o)");
    options->bake.add_to(*cmd, /*server_required=*/false);
    tree->excludes(cmd->get_option("--server"))->excludes(cmd->get_option("--spawn-server"));
    cmd->add_option("--mode", options->mode, "reference, lightcuts, cuts or cutsize")
        ->check(CLI::IsMember({"reference", "lightcuts", "cuts", "cutsize"}))
        ->capture_default_str();
    cmd->add_option("--criterion", options->criterion, "Cut criterion: radius (the thesis)")
        ->check(CLI::IsMember({"radius", "bound"}))
        ->capture_default_str();
    cmd->add_option("--size", options->size, "Image size WxH")->capture_default_str();
    auto* camera = cmd->add_option("--camera", options->camera,
                                   "Camera ex,ey,ez,tx,ty,tz,fovy (fovy in degrees)");
    cmd->add_option("--camera-index", options->camera_index, "Camera of the file to use")
        ->excludes(camera);
    cmd->add_option("--exposure", options->exposure, "Linear exposure before the tone curve")
        ->capture_default_str();
    cmd->add_option("-o,--output", options->output, "8-bit PNG to write")->required();
    cmd->add_option("--float", options->float_output, "Linear float PFM to write");
    cmd->add_option("--stats", options->stats, "Statistics JSON to write");
    cmd->add_flag("--validation", options->validation,
                  "Enable the Vulkan validation layer (also LC_VALIDATION=1)");
    cmd->callback([options] { run_render(*options); });
}

}  // namespace lc::client
