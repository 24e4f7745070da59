// editor_client view SCENE [--tree TREE.lcut | --server HOST:PORT | --spawn-server]
//   [--token-file F] [--script FILE] [--mode M] [--realtime-cut K] [--size WxH] [--camera ... | --camera-index I]
//   [--exposure E] [--frames N --screenshot OUT.png] [--headless] [--no-adaptive] [--no-panels]
//   [--no-progressive | --frame-budget-ms MS]
//   [--environment FILE.hdr [--environment-intensity S] [--environment-rotation DEG] | --sky E,A,T]
// The interactive editor: drag with the left button to orbit, the right button
// to pan, the wheel to dolly; keys 1-5 pick reference, lightcuts, cuts,
// cutsize, realtime; Esc or Q closes. `--script` runs editor commands through the same
// session functions the panels call, one command per frame. The view refines
// progressively (coarse to fine, in tiles within a GPU budget per frame) unless
// --no-progressive; with --tree it opens in lightcuts mode, as render does.
// The real-time mode shows whole frames and refines by accumulating them.
// --environment/--sky (or the glTF's environment) is the background where no
// geometry is hit, and Build Lighting sends it with the scene's surfaces.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "editor_client/commands/restir_options.h"
#include "editor_client/commands/bake_options.h"
#include "editor_client/commands/command_errors.h"
#include "editor_client/commands/commands.h"
#include "editor_client/commands/enum_flags.h"
#include "editor_client/commands/gltf_load_flags.h"
#include "editor_client/commands/shared_render_flags.h"
#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/script_runner.h"
#include "editor_client/render/render_inputs.h"
#include "editor_client/report/progress_display.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/vk/context.h"
#include "editor_client/window/editor_loop.h"
#include "editor_client/window/glfw_window.h"
#include "editor_client/window/headless_window.h"

namespace lc::client {
namespace {

struct ViewCommandOptions {
    std::string scene;
    GltfLoadOptions gltf;
    std::string tree;
    BakeFlags bake;
    std::string script;
    std::optional<RenderMode> mode;  // none: lightcuts with --tree, else reference
    SharedRenderFlags shared;        // the real-time budget, representatives, shadows, primary
    RestirFlags restir;
    std::string size = "800x600";
    std::string camera;
    std::optional<int> camera_index;
    std::optional<float> exposure;  // none: automatic, from the first full-size shaded frame
    uint32_t frames = 0;
    std::string screenshot;
    bool validation = false;
    bool headless = false;
    bool no_adaptive = false;
    float orbit_drag = 0.0f;
    bool no_panels = false;
    std::string window_screenshot;
    bool no_progressive = false;
    double frame_budget_ms = 30.0;
};

// The progressive view's story: when each image started, restarted and completed.
void print_refinement(const EditorLoopSummary& summary) {
    for (const RefinementEvent& e : summary.refinement_events) {
        if (e.kind == RefinementEvent::Kind::kRestarted)
            std::printf("refinement: frame %u at %.3f s restarted, pass %u of %u was %.1f%% done\n", e.frame,
                        e.seconds, std::min(e.pass + 1, e.passes), e.passes, e.percent);
        else
            std::printf("refinement: frame %u at %.3f s %s\n", e.frame, e.seconds,
                        refinement_event_name(e.kind));
    }
    const double fps = summary.refining_seconds > 0.0 ? summary.refining_frames / summary.refining_seconds : 0.0;
    std::printf("progressive: %u frames while refining in %.3f s = %.2f fps; first complete image ",
                summary.refining_frames, summary.refining_seconds, fps);
    if (summary.first_complete_seconds)
        std::printf("in %.3f s\n", *summary.first_complete_seconds);
    else
        std::printf("not reached\n");
}

// The first view the command line asks for (mode, size, camera, exposure), checked.
RenderSettings requested_view(const ViewCommandOptions& options, const Scene& scene) {
    const auto [width, height] = or_fail(parse_size(options.size));
    if (!options.screenshot.empty() && options.frames == 0 && options.script.empty())
        fail("--screenshot needs --frames N or --script (the frame to save is the last one)");
    const bool can_get_tree = !options.tree.empty() || options.bake.has_server();
    const RenderCamera camera =
        or_fail(choose_camera(scene, options.camera, options.camera_index, float(width) / float(height)));
    RenderSettings requested;
    const RenderMode first = options.tree.empty() ? RenderMode::kReference : RenderMode::kLightcuts;
    requested.mode = options.mode.value_or(first);
    requested.width = width;
    requested.height = height;
    requested.camera = camera;
    requested.exposure = options.exposure.value_or(1.0f);
    or_fail(validate(requested, {.has_tree = can_get_tree}));
    return requested;
}

// The session over the scene, showing the requested view, with the tree of --tree.
std::unique_ptr<EditorSession> open_session(const ViewCommandOptions& options, Scene scene,
                                            const RenderSettings& requested) {
    EditorSessionOptions session_options;
    session_options.aspect = float(requested.width) / float(requested.height);
    // The environment (the flags', else the glTF's) is the background, and goes with every bake.
    if (options.bake.has_server())
        session_options.bake = options.bake.to_options(scene);
    else
        session_options.bake.environment = or_fail(options.bake.environment.load(scene.environment));
    auto session = std::make_unique<EditorSession>(std::move(scene), session_options);
    or_fail(session->view_settings().set_camera(requested.camera));
    or_fail(session->view_settings().set_exposure(requested.exposure));
    session->view_settings().set_mode(requested.mode);
    or_fail(session->view_settings().set_representatives(options.shared.representatives));
    or_fail(session->view_settings().set_realtime_cut(options.shared.realtime_cut));
    or_fail(session->view_settings().set_realtime_rays(options.shared.realtime_rays));
    or_fail(session->view_settings().set_restir(or_fail(restir_settings_from(options.restir))));
    if (!options.tree.empty()) or_fail(session->import_tree_dump(options.tree));
    return session;
}

// A cut mode asked for on the command line with only a server: bake now.
// A fixed frame count waits for it, so those frames show the asked mode.
void bake_for_the_first_frame(const ViewCommandOptions& options, RenderMode mode, EditorSession& session) {
    if (!mode_needs_tree(mode) || !options.tree.empty()) return;
    or_fail(session.start_bake());
    if (options.frames == 0) return;
    ProgressDisplay progress(stderr);
    while (session.baking().bake_running()) {
        if (std::optional<BakeProgress> p = session.baking().bake_progress()) progress.update(p->stage, p->percent);
        if (session.baking().poll_bake()) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    progress.finish();
    const std::optional<BakeReport>& report = session.baking().last_bake();
    if (!report || !report->succeeded)
        fail("bake failed: " + (report ? report->error : std::string("no report")));
}

// A GLFW window (the context then makes its surface), or a headless one.
std::unique_ptr<Window> open_window(const ViewCommandOptions& options, uint32_t width, uint32_t height,
                                    vk::ContextOptions& context_options) {
    if (options.headless) return std::make_unique<HeadlessWindow>(width, height);
    std::unique_ptr<GlfwWindow> glfw =
        or_fail(GlfwWindow::create(width, height, "lightcuts editor: " + options.scene));
    context_options.instance_extensions = glfw->required_instance_extensions();
    GlfwWindow* raw = glfw.get();
    context_options.create_surface = [raw](VkInstance instance) { return raw->create_surface(instance); };
    return glfw;
}

EditorLoopOptions loop_options(const ViewCommandOptions& options, const RenderSettings& requested,
                               ScriptRunner* script) {
    EditorLoopOptions loop;
    loop.width = requested.width;
    loop.height = requested.height;
    loop.frames = options.frames;
    loop.screenshot = options.screenshot;
    loop.script = script;
    loop.adaptive_resolution = !options.no_adaptive;
    loop.auto_exposure = !options.exposure;
    if (!std::isfinite(options.orbit_drag)) fail("--orbit must be a finite number of pixels");
    loop.orbit_drag_per_frame = options.orbit_drag;
    loop.panels = !options.no_panels;
    loop.window_screenshot = options.window_screenshot;
    loop.shadows = options.shared.shadows;
    loop.primary = options.shared.primary;
    loop.progressive = !options.no_progressive;
    if (!(options.frame_budget_ms > 0.0) || !std::isfinite(options.frame_budget_ms))
        fail("--frame-budget-ms must be a positive number of milliseconds");
    loop.refinement.frame_budget_ms = options.frame_budget_ms;
    return loop;
}

void print_summary(const EditorLoopSummary& summary, const ViewCommandOptions& options,
                   const vk::Context& context, const EditorSession& session) {
    const double steady_fps =
        summary.steady_seconds > 0.0 ? summary.steady_frames / summary.steady_seconds : 0.0;
    std::printf(
        "%u frames, last in %s mode, %.2f ms GPU, %u validation messages%s%s\n"
        "steady: %u frames in %.3f s = %.2f fps at %ux%u, %zu lights\n",
        summary.frames, render_mode_name(summary.last_mode), summary.last_frame.gpu_ms,
        context.validation_message_count(), options.screenshot.empty() ? "" : " -> ",
        options.screenshot.c_str(), summary.steady_frames, summary.steady_seconds, steady_fps,
        summary.last_frame.width, summary.last_frame.height, session.scene().lights.size());
    // The real-time mode's accumulation, for scripted sessions to check.
    if (summary.last_frame.realtime_frames)
        std::printf("realtime history: %u frames\n", *summary.last_frame.realtime_frames);
}

void run_view(const ViewCommandOptions& options) {
    std::vector<std::string> warnings;
    Scene scene = or_fail(load_scene(options.scene, warnings, options.gltf));
    for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
    const RenderSettings requested = requested_view(options, scene);
    std::optional<ScriptRunner> script;
    if (!options.script.empty()) script.emplace(or_fail(load_editor_script(options.script)), options.script);
    std::unique_ptr<EditorSession> session = open_session(options, std::move(scene), requested);
    bake_for_the_first_frame(options, requested.mode, *session);

    vk::ContextOptions context_options;
    context_options.validation = options.validation;
    std::unique_ptr<Window> window = open_window(options, requested.width, requested.height, context_options);
    vk::Context context = or_fail(vk::Context::create(context_options));
    const EditorLoopOptions loop = loop_options(options, requested, script ? &*script : nullptr);
    EditorLoopSummary summary = or_fail(run_editor_loop(*window, context, *session, loop));
    print_summary(summary, options, context, *session);
    // The real-time mode refines by accumulating whole frames, not in tiles.
    if (loop.progressive && summary.last_mode != RenderMode::kRealtime) print_refinement(summary);
    if (script && script->state() == ScriptState::kFailed) fail(script->error());
}

}  // namespace

void register_view_command(CLI::App& app) {
    auto options = std::make_shared<ViewCommandOptions>();
    CLI::App* cmd =
        app.add_subcommand("view",
                           "The interactive editor (left drag: orbit, right drag: pan, wheel: dolly, "
                           "W/A/S/D/R/F: fly, Shift + left drag: look around, "
                           "1-4: reference/lightcuts/cuts/cutsize, Esc: quit)");
    cmd->add_option("scene", options->scene, "glTF 2.0 scene (.gltf/.glb) with KHR_lights_punctual")
        ->required();
    add_gltf_load_flags(*cmd, options->gltf);
    auto* tree = cmd->add_option("--tree", options->tree, "Light tree: a result channel dump (bake -o)");
    options->bake.add_to(*cmd, /*server_required=*/false);
    tree->excludes(cmd->get_option("--server"))->excludes(cmd->get_option("--spawn-server"));
    cmd->add_option("--mode", options->mode,
                    "First mode: reference, lightcuts, cuts, cutsize, realtime (stochastic lightcuts, "
                    "accumulated while the view rests) or restir (ReSTIR DI) (default: lightcuts with --tree, "
                    "reference otherwise)")
        ->transform(checked_names(kRenderModeNames));
    add_shared_render_flags(*cmd, options->shared);
    add_restir_options(cmd, &options->restir);
    cmd->add_option("--size", options->size, "Window and render size WxH")->capture_default_str();
    auto* camera =
        cmd->add_option("--camera", options->camera, "Start camera ex,ey,ez,tx,ty,tz,fovy (fovy in degrees)");
    cmd->add_option("--camera-index", options->camera_index, "Camera of the file to start from")
        ->excludes(camera);
    cmd->add_option("--exposure", options->exposure,
                    "Linear exposure before the tone curve (default: automatic, from the first "
                    "full-size reference or lightcuts frame, as render does)");
    cmd->add_option("--frames", options->frames, "Render this many frames, then exit");
    cmd->add_option("--screenshot", options->screenshot, "Save the last frame as PNG (with --frames)");
    cmd->add_option("--script", options->script,
                    "Editor commands, one per line (add-light, bake, mode, screenshot, save, ...)")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--headless", options->headless,
                  "Render without a window (frames are not shown; for scripts and benchmarks)");
    cmd->add_flag("--no-adaptive", options->no_adaptive,
                  "Always render at full size, also while the camera moves");
    cmd->add_option("--orbit", options->orbit_drag,
                    "Orbit the camera by this many pixels of drag every frame (measures the "
                    "frame rate while the camera moves, at reduced resolution)");
    cmd->add_option("--window-screenshot", options->window_screenshot,
                    "At the end, save the window as shown, panels included (PNG)");
    cmd->add_flag("--no-panels", options->no_panels, "Hide the editor panels and the overlay");
    auto* no_progressive = cmd->add_flag(
        "--no-progressive", options->no_progressive,
        "Render every frame whole (the window waits for it) instead of refining the view over "
        "frames, coarse to fine, in tiles");
    cmd->add_option("--frame-budget-ms", options->frame_budget_ms,
                    "Progressive view: GPU time per frame for its tiles, in milliseconds")
        ->capture_default_str()
        ->excludes(no_progressive);
    cmd->add_flag("--validation", options->validation,
                  "Enable the Vulkan validation layer (also LC_VALIDATION=1)");
    cmd->callback([options] { run_view(*options); });
}

}  // namespace lc::client
