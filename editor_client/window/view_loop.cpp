#include "editor_client/window/view_loop.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <optional>
#include <thread>
#include <vector>

#include "editor_client/render/image_io.h"
#include "editor_client/vk/barriers.h"
#include "editor_client/vk/swapchain.h"
#include "editor_client/vk/sync.h"
#include "editor_client/vk/vk_result.h"
#include "editor_client/window/orbit_camera.h"
#include "editor_client/window/presentation.h"

namespace lc::client {
namespace {

RenderMode mode_for_key(int key) { return static_cast<RenderMode>(key - 1); }

}  // namespace

Result<ViewSummary> run_view_loop(Window& window, const vk::Context& context, Renderer& renderer,
                                  const ViewOptions& options) {
    const vk::Device& device = context.device();
    const bool presenting = window.has_surface();
    if (presenting && context.surface() == VK_NULL_HANDLE)
        return make_error("the Vulkan context was created without the window's surface");

    Result<VkCommandBuffer> cmd = context.command_pool().allocate();
    if (!cmd) return make_error(cmd.error());
    Result<vk::Fence> frame_done = vk::Fence::create(device.handle());
    if (!frame_done) return make_error(frame_done.error());
    Result<vk::Semaphore> image_ready = vk::Semaphore::create(device.handle());
    if (!image_ready) return make_error(image_ready.error());

    std::optional<Presentation> presentation;
    bool recreate = presenting;

    RenderSettings settings = options.settings;
    OrbitCamera orbit(settings.camera);
    ViewSummary summary;
    auto started = std::chrono::steady_clock::now();
    while (options.frames == 0 || summary.frames < options.frames) {
        WindowInput input = window.poll();
        if (input.close_requested) break;
        orbit.orbit(input.orbit_drag);
        orbit.pan(input.pan_drag);
        orbit.dolly(input.scroll);
        settings.camera = orbit.camera();
        if (input.mode_key) {
            RenderMode wanted = mode_for_key(*input.mode_key);
            if (mode_needs_tree(wanted) && !renderer.has_tree()) {
                spdlog::warn(
                    "mode '{}' needs a light tree: start view with --tree, --server or "
                    "--spawn-server",
                    render_mode_name(wanted));
            } else {
                settings.mode = wanted;
            }
        }

        uint32_t image_index = 0;
        if (presenting) {
            VkExtent2D extent = window.framebuffer_size();
            if (extent.width == 0 || extent.height == 0) {  // minimised: nothing to show
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
                continue;
            }
            Result<bool> remade = ensure_presentation(context, extent, presentation, recreate);
            if (!remade) return make_error(remade.error());
            Result<bool> stale = acquire_image(*presentation, *image_ready, image_index);
            if (!stale) return make_error(stale.error());
            if (*stale) {
                recreate = true;
                continue;
            }
        }

        LC_RETURN_IF_ERROR(begin_frame_commands(*cmd));
        Status recorded = renderer.record(*cmd, settings);
        if (recorded && presenting)
            record_blit(*cmd, renderer.display_image(),
                        presentation->swapchain.images()[image_index],
                        presentation->swapchain.extent());
        LC_VK_CHECK(vkEndCommandBuffer(*cmd));
        if (!recorded) {
            // The acquired image must still be consumed; the simplest is to stop here.
            LC_RETURN_IF_ERROR(device.wait_idle());
            return make_error(recorded.error());
        }

        Result<bool> out_of_date =
            submit_and_present(device, presenting ? &*presentation : nullptr, *cmd, *image_ready, image_index,
                               *frame_done);
        if (!out_of_date) return make_error(out_of_date.error());
        if (*out_of_date) recreate = true;

        ++summary.frames;
        Result<PassTimings> timings = renderer.read_timings();
        if (timings) summary.last_render_ms = timings->total_ms;
        double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        window.set_title("lightcuts view: " + std::string(render_mode_name(settings.mode)) + ", " +
                         std::to_string(int(summary.last_render_ms)) + " ms GPU, " +
                         std::to_string(int(summary.frames / std::max(seconds, 1e-3))) + " fps");
    }
    LC_RETURN_IF_ERROR(device.wait_idle());
    summary.last_settings = settings;

    if (!options.screenshot.empty()) {
        if (summary.frames == 0) return make_error("no frame was rendered, so no screenshot");
        Result<std::vector<uint8_t>> pixels = renderer.read_display();
        if (!pixels) return make_error(pixels.error());
        LC_RETURN_IF_ERROR(
            write_png(options.screenshot, renderer.width(), renderer.height(), *pixels));
    }
    return summary;
}

}  // namespace lc::client
