#include "editor_client/window/editor_loop.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <optional>
#include <thread>
#include <utility>

#include <imgui.h>

#include "editor_client/editor/editor_panels.h"
#include "editor_client/render/error_stats.h"
#include "editor_client/render/image_io.h"
#include "editor_client/render/renderer.h"
#include "editor_client/vk/vk_result.h"
#include "editor_client/window/glfw_window.h"
#include "editor_client/window/imgui_layer.h"
#include "editor_client/window/orbit_camera.h"
#include "editor_client/window/presentation.h"
#include "editor_client/window/progressive_canvas.h"

namespace lc::client {
namespace {

// The renderer's last image: a PFM of the linear radiance, or a PNG of what is shown.
Status write_rendered_image(const Renderer& renderer, const std::filesystem::path& path) {
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    if (path.extension() == ".pfm") {
        Result<std::vector<float>> hdr = renderer.read_hdr();
        if (!hdr) return make_error(hdr.error());
        FloatImage image{renderer.width(), renderer.height(), {}};
        image.rgb.reserve(hdr->size() / 4 * 3);
        for (size_t i = 0; i < hdr->size(); i += 4) image.rgb.insert(image.rgb.end(), &(*hdr)[i], &(*hdr)[i + 3]);
        return write_pfm(path, image);
    }
    Result<std::vector<uint8_t>> pixels = renderer.read_display();
    if (!pixels) return make_error(pixels.error());
    return write_png(path, renderer.width(), renderer.height(), *pixels);
}

double elapsed_ms(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since).count();
}

// Keeps the renderer's lights and tree in step with the session: the renderer
// reads the scene's lights only when its tree is set, so every edit or import
// re-sets it. A tree baked for other lights is not shown: until the next bake
// the view renders the edited lights in reference mode instead.
class RendererSync {
public:
    RendererSync(Renderer& renderer, const EditorSession& session) : renderer_(renderer), session_(session) {}

    Status update() {
        if (in_step()) return Ok{};
        tree_ = session_.tree_matches_scene() ? session_.tree() : nullptr;
        if (tree_ && tree_->empty()) tree_.reset();
        LC_RETURN_IF_ERROR(renderer_.set_tree(tree_.get()));
        revision_ = session_.scene_revision();
        generation_ = session_.tree_generation();
        synced_ = true;
        ++updates_;
        return Ok{};
    }
    // Counts the renderer's lights and tree changing (a progressive image starts again).
    uint64_t updates() const { return updates_; }
    // Whether the renderer holds the session's lights and tree (no edit since update()).
    bool in_step() const {
        return synced_ && revision_ == session_.scene_revision() && generation_ == session_.tree_generation();
    }

    // The session's settings at a size, falling back to reference mode while
    // there is no tree matching the lights.
    RenderSettings settings(uint32_t width, uint32_t height) const {
        return render_settings_for(session_.view(), width, height, renderer_.has_tree());
    }

private:
    Renderer& renderer_;
    const EditorSession& session_;
    std::shared_ptr<const LightTree> tree_;  // what the GPU holds a copy of
    uint64_t revision_ = 0;
    uint64_t generation_ = 0;
    bool synced_ = false;
    uint64_t updates_ = 0;
};

// What a progressive image is being refined for: the settings and the
// renderer's lights and tree (RendererSync::updates) it started with.
struct RefinedImage {
    RenderSettings settings;
    uint64_t updates = 0;
};

// Screenshots render the current state afresh at full size, so a scripted
// screenshot right after an edit shows the edit (not the last, possibly
// reduced, frame). Called between frames, when the GPU is idle. With a
// progressive view (`refinement`), saving the view saves the image as refined
// so far, and a screenshot that overwrote an unfinished image asks for a restart.
class LoopHost final : public EditorHost {
public:
    LoopHost(Renderer& renderer, RendererSync& sync, uint32_t width, uint32_t height,
             const ProgressiveRefinement* refinement, const RefinedImage* refined)
        : renderer_(renderer),
          sync_(sync),
          width_(width),
          height_(height),
          refinement_(refinement),
          refined_(refined) {}

    Status screenshot(const std::filesystem::path& path) override {
        if (path.empty()) return make_error("screenshot needs a file name");
        LC_RETURN_IF_ERROR(sync_.update());
        Result<RenderStats> rendered = renderer_.render(sync_.settings(width_, height_));
        if (!rendered) return make_error("screenshot: " + rendered.error());
        if (refinement_ != nullptr && !refinement_->complete()) image_lost_ = true;
        if (Status written = write_rendered_image(renderer_, path); !written)
            return make_error("screenshot: " + written.error());
        ++count_;
        return Ok{};
    }
    Status save_view(const std::filesystem::path& path) override {
        if (refinement_ == nullptr) return screenshot(path);
        if (path.empty()) return make_error("save-view needs a file name");
        if (Status written = write_rendered_image(renderer_, path); !written)
            return make_error("save-view: " + written.error());
        return Ok{};
    }
    // Refined for what the next frame would show: a setting or light changed
    // since the image completed (the loop restarts it next frame) is not.
    // The real-time mode's view is refined once its history has outgrown the spatial filter.
    bool view_refined() const override {
        const RenderSettings settings = sync_.settings(width_, height_);
        if (settings.mode == RenderMode::kRealTime)
            return sync_.in_step() && renderer_.real_time_frames() >= kRealTimeRefinedFrames;
        if (refinement_ == nullptr) return true;
        return refinement_->complete() && sync_.in_step() && refined_->updates == sync_.updates() &&
               settings == refined_->settings;
    }
    void request_quit() override { quit_ = true; }

    bool quit_requested() const { return quit_; }
    uint32_t count() const { return count_; }
    // Whether a screenshot replaced the renderer's unfinished image (once).
    bool take_image_lost() { return std::exchange(image_lost_, false); }

private:
    Renderer& renderer_;
    RendererSync& sync_;
    uint32_t width_, height_;
    const ProgressiveRefinement* refinement_;
    const RefinedImage* refined_;
    bool quit_ = false;
    bool image_lost_ = false;
    uint32_t count_ = 0;
};

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

}  // namespace

const char* refinement_event_name(RefinementEvent::Kind kind) {
    switch (kind) {
        case RefinementEvent::Kind::kStarted: return "started";
        case RefinementEvent::Kind::kRestarted: return "restarted";
        case RefinementEvent::Kind::kCompleted: return "completed";
    }
    return "started";
}

Result<EditorLoopSummary> run_editor_loop(Window& window, const vk::Context& context, EditorSession& session,
                                          const EditorLoopOptions& options) {
    if (options.width == 0 || options.height == 0)
        return make_error("the editor's render size must be at least 1x1");
    const vk::Device& device = context.device();
    const bool presenting = window.has_surface();
    if (presenting && context.surface() == VK_NULL_HANDLE)
        return make_error("the Vulkan context was created without the window's surface");

    // The renderer keeps a reference to the session's scene, whose lights
    // RendererSync re-reads after every edit.
    RendererOptions renderer_options;
    renderer_options.shadows = options.shadows;
    Result<std::unique_ptr<Renderer>> created =
        Renderer::create(context, session.scene(), nullptr, renderer_options);
    if (!created) return make_error(created.error());
    Renderer& renderer = **created;
    LC_RETURN_IF_ERROR(renderer.set_environment(session.environment()));
    RendererSync sync(renderer, session);
    LC_RETURN_IF_ERROR(sync.update());
    std::optional<ProgressiveRefinement> refinement;
    std::optional<ProgressiveCanvas> canvas;
    AdaptiveResolutionOptions adaptive_options = options.adaptive;
    if (options.progressive) {
        if (!(options.refinement.frame_budget_ms > 0.0))
            return make_error("the frame budget must be a positive number of milliseconds");
        refinement.emplace(options.width, options.height, renderer.workgroup_size(), options.refinement);
        Result<ProgressiveCanvas> made = ProgressiveCanvas::create(device, options.width, options.height);
        if (!made) return make_error(made.error());
        canvas.emplace(std::move(made).value());
        // The coarse pass is the size whose whole image fits one frame's budget.
        adaptive_options.target_frame_ms = options.refinement.frame_budget_ms;
    }
    RefinedImage refined;  // what the progressive image shows
    LoopHost host(renderer, sync, options.width, options.height, refinement ? &*refinement : nullptr,
                  &refined);

    Result<VkCommandBuffer> cmd = context.command_pool().allocate();
    if (!cmd) return make_error(cmd.error());
    Result<vk::Fence> frame_done = vk::Fence::create(device.handle());
    if (!frame_done) return make_error(frame_done.error());
    Result<vk::Semaphore> image_ready = vk::Semaphore::create(device.handle());
    if (!image_ready) return make_error(image_ready.error());
    std::optional<Presentation> presentation;
    bool recreate = presenting;
    GlfwWindow* glfw = options.panels ? dynamic_cast<GlfwWindow*>(&window) : nullptr;
    std::unique_ptr<ImGuiLayer> ui;  // made with the first swapchain (it needs its format)
    PanelState panel_state;

    OrbitCamera orbit(session.view().camera);
    RenderCamera orbit_camera = session.view().camera;
    AdaptiveResolution adaptive(adaptive_options);
    EditorLoopSummary summary;
    bool auto_exposure_pending = options.auto_exposure;
    const float initial_exposure = session.view().exposure;
    const auto started = std::chrono::steady_clock::now();
    std::optional<std::chrono::steady_clock::time_point> steady_since;
    if (options.script == nullptr) steady_since = started;

    while (options.frames == 0 || summary.frames < options.frames) {
        const auto frame_start = std::chrono::steady_clock::now();
        if (ui) ui->discard_open_frame();
        WindowInput input = window.poll();
        if (input.close_requested) break;
        input.orbit_drag.x += options.orbit_drag_per_frame;
        if (ui) {
            // The panels act on the session before this frame's settings are
            // taken, so what they change shows in this very frame.
            ui->begin_frame();
            const ImGuiIO& io = ImGui::GetIO();
            std::optional<ViewClick> click;
            if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !io.WantCaptureMouse)
                click = ViewClick{io.MousePos.x, io.MousePos.y, uint32_t(std::max(io.DisplaySize.x, 1.0f)),
                                  uint32_t(std::max(io.DisplaySize.y, 1.0f))};
            draw_editor_panels(session, host, panel_state, summary.last_frame, click);
            glfw->set_ui_capture(ui->wants_mouse(), ui->wants_keyboard());
        }

        // A script or a panel may have moved the camera: orbit from there.
        if (session.view().camera != orbit_camera) {
            orbit = OrbitCamera(session.view().camera);
            orbit_camera = session.view().camera;
        }
        const bool moved = input.orbit_drag != glm::vec2(0.0f) || input.pan_drag != glm::vec2(0.0f) ||
                           input.look_drag != glm::vec2(0.0f) || input.fly != glm::vec3(0.0f) ||
                           input.scroll != 0.0f;
        if (moved) {
            orbit.orbit(input.orbit_drag);
            orbit.pan(input.pan_drag);
            orbit.look(input.look_drag);
            orbit.dolly(input.scroll);
            // Fly by the last frame's time (capped, so one slow frame is not a leap).
            const double frame_s = std::min(summary.last_frame.frame_ms, 250.0) / 1000.0;
            orbit.fly(input.fly, orbit.fly_speed() * float(std::max(frame_s, 1.0 / 60.0)));
            RenderCamera next = orbit.camera();
            next.up = session.view().camera.up;
            if (session.set_camera(next)) orbit_camera = session.view().camera;
        }
        if (input.mode_key && *input.mode_key >= 1 && *input.mode_key <= kRenderModeCount)
            session.set_mode(static_cast<RenderMode>(*input.mode_key - 1));

        if (std::optional<BakeReport> report = session.poll_bake()) log_bake(*report);
        if (options.script != nullptr && !steady_since) {
            const ScriptState state = options.script->step(session, host);
            summary.script_state = state;
            if (state == ScriptState::kFailed) {
                LC_RETURN_IF_ERROR(device.wait_idle());
                return make_error(options.script->error());
            }
            if (state == ScriptState::kFinished || state == ScriptState::kQuit)
                steady_since = std::chrono::steady_clock::now();
        }
        if (host.quit_requested()) break;
        LC_RETURN_IF_ERROR(sync.update());

        uint32_t image_index = 0;
        if (presenting) {
            VkExtent2D extent = window.framebuffer_size();
            if (extent.width == 0 || extent.height == 0) {  // minimised: nothing to show
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
                continue;
            }
            Result<bool> remade = ensure_presentation(context, extent, presentation, recreate);
            if (!remade) return make_error(remade.error());
            if (*remade) {
                if (glfw != nullptr && !ui) {
                    Result<std::unique_ptr<ImGuiLayer>> layer = ImGuiLayer::create(glfw->handle(), context);
                    if (!layer) return make_error("editor panels: " + layer.error());
                    ui = std::move(layer).value();
                }
                if (ui) LC_RETURN_IF_ERROR(ui->resize(presentation->swapchain.extent()));
            }
            Result<bool> stale = acquire_image(*presentation, *image_ready, image_index);
            if (!stale) return make_error(stale.error());
            if (*stale) {
                recreate = true;
                continue;
            }
        }

        // After the swapchain image is in hand: a skipped frame must not take tiles.
        const auto since_start = [&] { return elapsed_ms(started) / 1000.0; };
        uint32_t divisor = 1;
        RenderSettings settings = sync.settings(options.width, options.height);
        // The real-time mode shows whole frames at the full size: its history
        // refines the view, not tiles or a coarser size.
        const bool realtime = settings.mode == RenderMode::kRealTime;
        const bool tiled = refinement && !realtime;
        std::optional<TileBatch> batch;
        if (tiled) {
            const bool lost = host.take_image_lost();
            // The same image: every setting equal (an exposure change tone-maps anew, so it refines anew).
            if (summary.refinement_events.empty() || lost || settings != refined.settings ||
                sync.updates() != refined.updates) {
                RefinementEvent event;
                event.kind = summary.refinement_events.empty() ? RefinementEvent::Kind::kStarted
                                                               : RefinementEvent::Kind::kRestarted;
                event.frame = summary.frames;
                event.seconds = since_start();
                event.percent = refinement->percent();
                event.pass = refinement->pass();
                event.passes = refinement->passes();
                summary.refinement_events.push_back(event);
                refinement->restart(adaptive.divisor_meeting_target());
                refined.settings = settings;
                refined.updates = sync.updates();
            }
            batch = refinement->next_batch();
            if (batch) {
                divisor = batch->divisor;
                settings.width = batch->width;
                settings.height = batch->height;
            }
        } else if (!realtime) {
            divisor = options.adaptive_resolution ? adaptive.next_divisor(moved, elapsed_ms(started)) : 1;
            settings = sync.settings(reduced_size(options.width, divisor), reduced_size(options.height, divisor));
        }

        LC_RETURN_IF_ERROR(begin_frame_commands(*cmd));
        Status recorded = Ok{};
        const vk::Image* shown = &renderer.display_image();
        DisplayWrite written;
        if (tiled) {
            if (batch) recorded = renderer.record_regions(*cmd, settings, batch->tiles, !batch->new_image);
            if (recorded)
                canvas->record_tiles(*cmd, renderer.display_image(),
                                     batch ? std::span<const PixelRegion>(batch->tiles) : std::span<const PixelRegion>(),
                                     divisor);
            shown = &canvas->image();
            written = {ProgressiveCanvas::kWriteStage, ProgressiveCanvas::kWriteAccess};
        } else {
            recorded = renderer.record(*cmd, settings);
        }
        const bool draw_panels = ui && ui->frame_open() && recorded && presenting;
        if (recorded && presenting) {
            const VkImage target = presentation->swapchain.images()[image_index];
            if (draw_panels) {
                record_blit(*cmd, *shown, ui->composite().handle(), presentation->swapchain.extent(), true,
                            written);
                ui->record(*cmd, target);
            } else {
                record_blit(*cmd, *shown, target, presentation->swapchain.extent(), false, written);
            }
        }
        LC_VK_CHECK(vkEndCommandBuffer(*cmd));
        if (!recorded) {
            LC_RETURN_IF_ERROR(device.wait_idle());
            return make_error(recorded.error());
        }

        Result<bool> out_of_date =
            submit_and_present(device, presenting ? &*presentation : nullptr, *cmd, *image_ready, image_index,
                               *frame_done);
        if (!out_of_date) return make_error(out_of_date.error());
        if (*out_of_date) recreate = true;

        ++summary.frames;
        // A progressive view sets the exposure from its first whole image, coarse or not.
        const bool whole_image = tiled ? batch && refinement->pass() > batch->pass : divisor == 1;
        if (auto_exposure_pending && whole_image && mode_is_shaded(settings.mode)) {
            auto_exposure_pending = false;
            // A script or the panel may have set one already: keep it.
            if (session.view().exposure == initial_exposure) {
                Result<std::vector<float>> hdr = renderer.read_hdr();
                if (!hdr) return make_error(hdr.error());
                LC_RETURN_IF_ERROR(session.set_exposure(auto_exposure(*hdr)));
                // The progressive image goes on refining: what it lit is tone-mapped again.
                if (tiled) {
                    refined.settings.exposure = session.view().exposure;
                    settings.exposure = refined.settings.exposure;
                    const PixelRegion whole{0, 0, settings.width, settings.height};
                    Status toned = Ok{};
                    LC_RETURN_IF_ERROR(context.command_pool().run_one_time(device, [&](VkCommandBuffer c) {
                        toned = renderer.record_output(c, settings, std::span(&whole, 1));
                        if (toned) canvas->record_tiles(c, renderer.display_image(), std::span(&whole, 1), divisor);
                    }));
                    LC_RETURN_IF_ERROR(toned);
                }
            }
        }
        FrameInfo& frame = summary.last_frame;
        frame.frame_ms = elapsed_ms(frame_start);
        if (tiled) {
            RefinementProgress progress;
            progress.pass = refinement->pass();
            progress.passes = refinement->passes();
            progress.percent = refinement->percent();
            progress.divisor = divisor;
            frame.refinement = progress;
            if (batch) {
                summary.refining_frames += 1;
                summary.refining_seconds += frame.frame_ms / 1000.0;
            }
            if (batch && refinement->complete()) {
                RefinementEvent event;
                event.kind = RefinementEvent::Kind::kCompleted;
                event.frame = summary.frames - 1;
                event.seconds = since_start();
                event.percent = 100.0;
                event.pass = event.passes = refinement->passes();
                summary.refinement_events.push_back(event);
                if (!summary.first_complete_seconds) summary.first_complete_seconds = event.seconds;
            }
        }
        if (!tiled || batch) {
            frame.width = settings.width;
            frame.height = settings.height;
            frame.divisor = divisor;
            if (Result<PassTimings> timings = renderer.read_timings()) {
                frame.gpu_ms = timings->total_ms;
                if (batch) {
                    // The budget is for the tiles: the G-buffer is drawn once per pass.
                    const double tiles_ms = timings->lighting_ms + timings->output_ms;
                    refinement->report(*batch, tiles_ms);
                    const double pass_pixels = double(batch->width) * double(batch->height);
                    adaptive.report_frame(divisor, tiles_ms * pass_pixels / double(batch->pixels()));
                }
            }
            frame.avg_cut.reset();
            frame.max_cut.reset();
            frame.loop_limit_stops = 0;
            if (settings.mode != RenderMode::kReference) {
                if (Result<GpuFrameCounters> counters = renderer.read_counters()) {
                    frame.max_cut = counters->max_cut;
                    frame.loop_limit_stops = counters->loop_limit_stops;
                }
            }
        } else {
            frame.gpu_ms = 0.0;
        }
        frame.realtime_frames.reset();
        if (realtime) frame.realtime_frames = renderer.real_time_frames();
        summary.last_mode = settings.mode;
        if (!tiled) adaptive.report_frame(divisor, frame.frame_ms);
        if (steady_since) ++summary.steady_frames;
        const std::vector<std::string> lines = overlay_lines(session, frame);
        window.set_title("lightcuts editor: " + (lines.empty() ? std::string() : lines[0]));
        // A finished progressive image has nothing left for the GPU: the loop
        // only answers input, without spinning a core.
        if (tiled && !batch) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    LC_RETURN_IF_ERROR(device.wait_idle());
    const auto ended = std::chrono::steady_clock::now();
    summary.seconds = std::chrono::duration<double>(ended - started).count();
    if (steady_since) summary.steady_seconds = std::chrono::duration<double>(ended - *steady_since).count();

    if (!options.screenshot.empty()) LC_RETURN_IF_ERROR(host.screenshot(options.screenshot));
    if (!options.window_screenshot.empty()) {
        if (!ui) return make_error("--window-screenshot needs a window with panels");
        Result<std::vector<uint8_t>> pixels = ui->read_composite();
        if (!pixels) return make_error(pixels.error());
        LC_RETURN_IF_ERROR(write_png(options.window_screenshot, ui->composite().desc().width,
                                     ui->composite().desc().height, *pixels));
    }
    summary.screenshots = host.count();
    return summary;
}

}  // namespace lc::client
