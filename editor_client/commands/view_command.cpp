// editor_client view SCENE [--tree TREE.lcut | --server HOST:PORT | --spawn-server] [--mode M]
//   [--size WxH] [--camera ... | --camera-index I] [--exposure E] [--frames N --screenshot OUT.png]
// A window with the rendered scene: drag with the left button to orbit, the
// right button to pan, the wheel to dolly; keys 1-4 pick reference, lightcuts,
// cuts, cutsize; Esc or Q closes.
#include <spdlog/spdlog.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "editor_client/commands/bake_options.h"
#include "editor_client/commands/commands.h"
#include "editor_client/render/render_inputs.h"
#include "editor_client/render/renderer.h"
#include "editor_client/report/progress_display.h"
#include "editor_client/scene/gltf_loader.h"
#include "editor_client/vk/context.h"
#include "editor_client/window/glfw_window.h"
#include "editor_client/window/view_loop.h"

namespace lc::client {
namespace {

struct ViewCommandOptions {
    std::string scene;
    std::string tree;
    BakeFlags bake;
    std::string mode = "reference";
    std::string size = "800x600";
    std::string camera;
    std::optional<int> camera_index;
    float exposure = 1.0f;
    uint32_t frames = 0;
    std::string screenshot;
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

void run_view(const ViewCommandOptions& options) {
    std::vector<std::string> warnings;
    Scene scene = or_fail(load_scene(options.scene, warnings));
    for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";

    ViewOptions view;
    std::optional<RenderMode> mode = parse_render_mode(options.mode);
    if (!mode) fail("unknown --mode '" + options.mode + "' (reference, lightcuts, cuts, cutsize)");
    view.settings.mode = *mode;
    auto [width, height] = or_fail(parse_size(options.size));
    view.settings.width = width;
    view.settings.height = height;
    if (!std::isfinite(options.exposure) || options.exposure < 0.0f)
        fail("--exposure must be a finite number >= 0");
    view.settings.exposure = options.exposure;
    view.settings.camera = or_fail(
        choose_camera(scene, options.camera, options.camera_index, float(width) / float(height)));
    view.frames = options.frames;
    view.screenshot = options.screenshot;
    if (!options.screenshot.empty() && options.frames == 0)
        fail("--screenshot needs --frames N (the frame to save is the last one)");

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
    if (mode_needs_tree(view.settings.mode) && source.empty())
        fail("mode '" + options.mode +
             "' needs a light tree: give --tree TREE.lcut, --server "
             "HOST:PORT or --spawn-server");
    std::shared_ptr<const LightTree> tree = or_fail(obtain_tree(scene, source));
    progress.finish();

    std::unique_ptr<GlfwWindow> window =
        or_fail(GlfwWindow::create(width, height, "lightcuts view: " + options.scene));
    vk::ContextOptions context_options;
    context_options.validation = options.validation;
    context_options.instance_extensions = window->required_instance_extensions();
    context_options.create_surface = [&](VkInstance instance) {
        return window->create_surface(instance);
    };
    vk::Context context = or_fail(vk::Context::create(context_options));
    std::unique_ptr<Renderer> renderer = or_fail(Renderer::create(context, scene, tree.get()));
    for (const EffectDecision& d : renderer->effects().decisions)
        spdlog::info("effect: {}: {}, {}", d.name, d.simulated ? "simulated" : "skipped", d.reason);

    ViewSummary summary = or_fail(run_view_loop(*window, context, *renderer, view));
    std::printf("%u frames, last in %s mode, %.2f ms GPU, %u validation messages%s%s\n",
                summary.frames, render_mode_name(summary.last_settings.mode),
                summary.last_render_ms, context.validation_message_count(),
                options.screenshot.empty() ? "" : " -> ", options.screenshot.c_str());
}

}  // namespace

void add_view_command(CLI::App& app) {
    auto options = std::make_shared<ViewCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "view",
        "Show a scene in a window (left drag: orbit, right drag: pan, wheel: dolly, "
        "1-4: reference/lightcuts/cuts/cutsize, Esc: quit)");
    cmd->add_option("scene", options->scene, "glTF 2.0 scene (.gltf/.glb) with KHR_lights_punctual")
        ->required();
    auto* tree =
        cmd->add_option("--tree", options->tree, "Light tree: a result channel dump (bake -o)");
    options->bake.add_to(*cmd, /*server_required=*/false);
    tree->excludes(cmd->get_option("--server"))->excludes(cmd->get_option("--spawn-server"));
    cmd->add_option("--mode", options->mode, "First mode: reference, lightcuts, cuts or cutsize")
        ->check(CLI::IsMember({"reference", "lightcuts", "cuts", "cutsize"}))
        ->capture_default_str();
    cmd->add_option("--size", options->size, "Window and render size WxH")->capture_default_str();
    auto* camera = cmd->add_option("--camera", options->camera,
                                   "Start camera ex,ey,ez,tx,ty,tz,fovy (fovy in degrees)");
    cmd->add_option("--camera-index", options->camera_index, "Camera of the file to start from")
        ->excludes(camera);
    cmd->add_option("--exposure", options->exposure, "Linear exposure before the tone curve")
        ->capture_default_str();
    cmd->add_option("--frames", options->frames, "Render this many frames, then exit");
    cmd->add_option("--screenshot", options->screenshot,
                    "Save the last frame as PNG (with --frames)");
    cmd->add_flag("--validation", options->validation,
                  "Enable the Vulkan validation layer (also LC_VALIDATION=1)");
    cmd->callback([options] { run_view(*options); });
}

}  // namespace lc::client
