#include "editor_client/window/editor_loop.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <optional>
#include <span>
#include <thread>
#include <utility>

#include <imgui.h>

#include "editor_client/editor/editor_panels.h"
#include "editor_client/render/output/image_io.h"
#include "editor_client/render/renderer.h"
#include "editor_client/window/editor_loop_host.h"
#include "editor_client/window/frame_presenter.h"
#include "editor_client/window/progressive_canvas.h"
#include "editor_client/window/renderer_sync.h"
#include "editor_client/window/view_auto_exposure.h"
#include "editor_client/window/view_controls.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point since) {
    return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

void log_bake(const BakeReport& report) {
    for (const std::string& w : report.warnings) spdlog::warn("server warning: {}", w);
    if (report.succeeded)
        spdlog::info("bake: {} lights -> {} nodes in {:.0f} ms (build {:.0f} ms)", report.light_count,
                     report.node_count, report.total_ms, report.build_ms);
    else if (report.cancelled)
        spdlog::info("bake cancelled; the previous tree stays");
    else
        spdlog::error("bake failed: {}; the previous tree stays", report.error);
}

FrameScheduleOptions schedule_options(const EditorLoopOptions& options, uint32_t tile_alignment) {
    FrameScheduleOptions schedule;
    schedule.width = options.width;
    schedule.height = options.height;
    schedule.adaptive_resolution = options.adaptive_resolution;
    schedule.adaptive = options.adaptive;
    schedule.progressive = options.progressive;
    schedule.refinement = options.refinement;
    schedule.tile_alignment = tile_alignment;
    return schedule;
}

// One editor session's frames. prepare() makes the renderer and the
// presentation; run() repeats the steps input, update, schedule, render and
// present, then accounts for the frame, until the window closes, the script
// quits or the frame count is reached.
class EditorLoop {
public:
    EditorLoop(Window& window, const vk::Context& context, EditorSession& session,
               const EditorLoopOptions& options)
        : window_(window),
          context_(context),
          session_(session),
          options_(options),
          controls_(session.view().camera),
          auto_exposure_(options.auto_exposure, session.view().exposure) {}

    Status prepare();
    Result<EditorLoopSummary> run();

private:
    Result<bool> input(bool& moved);  // false: the window asks to close
    void draw_panels(ImGuiLayer& ui);
    Result<bool> update();  // false: the script or a panel quit
    FramePlan schedule(bool moved);
    Status render(const FramePlan& plan);
    Status account(FramePlan& plan, Clock::time_point frame_start);
    void read_gpu_statistics(const FramePlan& plan, FrameInfo& frame);
    Result<EditorLoopSummary> finish();
    Status save_window_screenshot();

    Window& window_;
    const vk::Context& context_;
    EditorSession& session_;
    const EditorLoopOptions& options_;
    // The renderer keeps a reference to the session's scene, whose lights
    // RendererSync re-reads after every edit.
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<RendererSync> sync_;
    std::optional<FrameSchedule> schedule_;
    std::optional<ProgressiveCanvas> canvas_;  // the progressive view's image
    std::unique_ptr<EditorLoopHost> host_;
    std::unique_ptr<FramePresenter> presenter_;
    PanelState panel_state_;
    ViewControls controls_;
    ViewAutoExposure auto_exposure_;
    EditorLoopSummary summary_;
    Clock::time_point started_;
    // Since the script finished (from the start without one): the steady frame rate's frames.
    std::optional<Clock::time_point> steady_since_;
};

Status EditorLoop::prepare() {
    if (options_.width == 0 || options_.height == 0)
        return make_error("the editor's render size must be at least 1x1");
    if (window_.has_surface() && context_.surface() == VK_NULL_HANDLE)
        return make_error("the Vulkan context was created without the window's surface");
    RendererOptions renderer_options;
    renderer_options.shadows = options_.shadows;
    renderer_options.primary = options_.primary;
    Result<std::unique_ptr<Renderer>> created =
        Renderer::create(context_, session_.scene(), nullptr, renderer_options);
    if (!created) return make_error(created.error());
    renderer_ = std::move(created).value();
    LC_RETURN_IF_ERROR(renderer_->set_environment(session_.environment()));
    sync_ = std::make_unique<RendererSync>(*renderer_, session_);
    LC_RETURN_IF_ERROR(sync_->update());
    if (options_.progressive && !(options_.refinement.frame_budget_ms > 0.0))
        return make_error("the frame budget must be a positive number of milliseconds");
    schedule_.emplace(schedule_options(options_, renderer_->workgroup_size()));
    if (options_.progressive) {
        Result<ProgressiveCanvas> made =
            ProgressiveCanvas::create(context_.device(), options_.width, options_.height);
        if (!made) return make_error(made.error());
        canvas_.emplace(std::move(made).value());
    }
    host_ = std::make_unique<EditorLoopHost>(*renderer_, *sync_, options_.width, options_.height, *schedule_);
    Result<std::unique_ptr<FramePresenter>> presenter =
        FramePresenter::create(context_, window_, options_.panels);
    if (!presenter) return make_error(presenter.error());
    presenter_ = std::move(presenter).value();
    return Ok{};
}

Result<EditorLoopSummary> EditorLoop::run() {
    started_ = Clock::now();
    if (options_.script == nullptr) steady_since_ = started_;
    while (options_.frames == 0 || summary_.frames < options_.frames) {
        const Clock::time_point frame_start = Clock::now();
        bool moved = false;
        Result<bool> open = input(moved);
        LC_RETURN_IF_ERROR(open);
        if (!*open) break;
        Result<bool> going = update();
        LC_RETURN_IF_ERROR(going);
        if (!*going) break;
        // A skipped frame (no swapchain image) must not take tiles: acquire before scheduling.
        Result<bool> acquired = presenter_->acquire();
        LC_RETURN_IF_ERROR(acquired);
        if (!*acquired) continue;
        FramePlan plan = schedule(moved);
        LC_RETURN_IF_ERROR(render(plan));
        LC_RETURN_IF_ERROR(account(plan, frame_start));
    }
    return finish();
}

// The input step: the window's events, the panels (which act on the session
// before this frame's settings are taken, so what they change shows in this
// very frame) and the camera.
Result<bool> EditorLoop::input(bool& moved) {
    ImGuiLayer* ui = presenter_->ui();
    if (ui != nullptr) ui->discard_open_frame();
    WindowInput events = window_.poll();
    if (events.close_requested) return false;
    events.orbit_drag.x += options_.orbit_drag_per_frame;
    if (ui != nullptr) draw_panels(*ui);
    moved = controls_.apply(events, session_, summary_.last_frame.frame_ms);
    return true;
}

void EditorLoop::draw_panels(ImGuiLayer& ui) {
    ui.begin_frame();
    const ImGuiIO& io = ImGui::GetIO();
    std::optional<ViewClick> click;
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !io.WantCaptureMouse)
        click = ViewClick{io.MousePos.x, io.MousePos.y, uint32_t(std::max(io.DisplaySize.x, 1.0f)),
                          uint32_t(std::max(io.DisplaySize.y, 1.0f))};
    draw_editor_panels(session_, *host_, panel_state_, summary_.last_frame, click);
    presenter_->glfw()->set_ui_capture(ui.wants_mouse(), ui.wants_keyboard());
}

// The update step: the bake in flight, the script, and the renderer brought in step with both.
Result<bool> EditorLoop::update() {
    if (std::optional<BakeReport> report = session_.baking().poll_bake()) log_bake(*report);
    if (options_.script != nullptr && !steady_since_) {
        const ScriptState state = options_.script->step(session_, *host_);
        summary_.script_state = state;
        if (state == ScriptState::kFailed) {
            LC_RETURN_IF_ERROR(context_.device().wait_idle());
            return make_error(options_.script->error());
        }
        if (state == ScriptState::kFinished || state == ScriptState::kQuit) steady_since_ = Clock::now();
    }
    if (host_->quit_requested()) return false;
    LC_RETURN_IF_ERROR(sync_->update());
    return true;
}

FramePlan EditorLoop::schedule(bool moved) {
    FrameInputs inputs;
    inputs.settings = sync_->settings(options_.width, options_.height);
    inputs.renderer_updates = sync_->updates();
    inputs.image_lost = schedule_->tiled(inputs.settings) && host_->take_image_lost();
    inputs.moved = moved;
    inputs.frame = summary_.frames;
    inputs.now_ms = elapsed_ms(started_);
    return schedule_->plan(inputs);
}

// The render and present steps: the plan's image, or its tiles copied onto the
// progressive canvas, shown in the window.
Status EditorLoop::render(const FramePlan& plan) {
    Result<VkCommandBuffer> cmd = presenter_->begin();
    LC_RETURN_IF_ERROR(cmd);
    Status recorded = Ok{};
    const vk::Image* shown = &renderer_->display_image();
    DisplayWrite written;
    if (plan.tiled) {
        if (plan.batch)
            recorded =
                renderer_->record_regions(*cmd, plan.settings, plan.batch->tiles, !plan.batch->new_image);
        if (recorded)
            canvas_->record_tiles(
                *cmd, renderer_->display_image(),
                plan.batch ? std::span<const PixelRegion>(plan.batch->tiles) : std::span<const PixelRegion>(),
                plan.divisor);
        shown = &canvas_->image();
        written = {ProgressiveCanvas::kWriteStage, ProgressiveCanvas::kWriteAccess};
    } else {
        recorded = renderer_->record(*cmd, plan.settings);
    }
    return presenter_->present(recorded, *shown, written);
}

// After the frame ran: auto-exposure, then what the frame measured, for the
// schedule, the overlay and the summary.
Status EditorLoop::account(FramePlan& plan, Clock::time_point frame_start) {
    ++summary_.frames;
    LC_RETURN_IF_ERROR(auto_exposure_.after_frame(plan, *schedule_, *renderer_, session_, context_, canvas_));
    FrameInfo& frame = summary_.last_frame;
    frame.frame_ms = elapsed_ms(frame_start);
    schedule_->finish_frame(plan, frame, summary_.frames - 1, elapsed_ms(started_));
    if (!plan.tiled || plan.batch)
        read_gpu_statistics(plan, frame);
    else
        frame.gpu_ms = 0.0;
    frame.realtime_frames.reset();
    if (plan.realtime)
        frame.realtime_frames = plan.settings.mode == RenderMode::kRestir ? renderer_->restir_frames()
                                                                          : renderer_->realtime_frames();
    summary_.last_mode = plan.settings.mode;
    if (steady_since_) ++summary_.steady_frames;
    const std::vector<std::string> lines = overlay_lines(session_, frame);
    window_.set_title("lightcuts editor: " + (lines.empty() ? std::string() : lines[0]));
    // A finished progressive image has nothing left for the GPU: the loop
    // only answers input, without spinning a core.
    if (plan.tiled && !plan.batch) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return Ok{};
}

void EditorLoop::read_gpu_statistics(const FramePlan& plan, FrameInfo& frame) {
    frame.width = plan.settings.width;
    frame.height = plan.settings.height;
    frame.divisor = plan.divisor;
    if (Result<PassTimings> timings = renderer_->read_timings()) {
        frame.gpu_ms = timings->total_ms;
        // The budget is for the tiles: the G-buffer is drawn once per pass.
        schedule_->report_gpu(plan, timings->lighting_ms + timings->output_ms);
    }
    frame.avg_cut.reset();
    frame.max_cut.reset();
    frame.loop_limit_stops = 0;
    if (plan.settings.mode != RenderMode::kReference) {
        if (Result<GpuFrameCounters> counters = renderer_->read_counters()) {
            frame.max_cut = counters->max_cut;
            frame.loop_limit_stops = counters->loop_limit_stops;
        }
    }
}

// The screenshots step, once the GPU is idle, and the summary.
Result<EditorLoopSummary> EditorLoop::finish() {
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    const Clock::time_point ended = Clock::now();
    summary_.seconds = std::chrono::duration<double>(ended - started_).count();
    if (steady_since_)
        summary_.steady_seconds = std::chrono::duration<double>(ended - *steady_since_).count();
    if (!options_.screenshot.empty()) LC_RETURN_IF_ERROR(host_->screenshot(options_.screenshot));
    if (!options_.window_screenshot.empty()) LC_RETURN_IF_ERROR(save_window_screenshot());
    summary_.screenshots = host_->count();
    // What the Server panel says, for a scripted session's log.
    if (panel_state_.server_status)
        for (const std::string& line : panel_state_.server_status->answered_lines())
            spdlog::info("server panel: {}", line);
    summary_.refinement_events = schedule_->events();
    summary_.first_complete_seconds = schedule_->first_complete_seconds();
    summary_.refining_frames = schedule_->refining_frames();
    summary_.refining_seconds = schedule_->refining_seconds();
    return summary_;
}

Status EditorLoop::save_window_screenshot() {
    const ImGuiLayer* ui = presenter_->ui();
    if (ui == nullptr) return make_error("--window-screenshot needs a window with panels");
    Result<std::vector<uint8_t>> pixels = ui->read_composite();
    if (!pixels) return make_error(pixels.error());
    return write_png(options_.window_screenshot, ui->composite().desc().width, ui->composite().desc().height,
                     *pixels);
}

}  // namespace

Result<EditorLoopSummary> run_editor_loop(Window& window, const vk::Context& context, EditorSession& session,
                                          const EditorLoopOptions& options) {
    EditorLoop loop(window, context, session, options);
    LC_RETURN_IF_ERROR(loop.prepare());
    return loop.run();
}

}  // namespace lc::client
