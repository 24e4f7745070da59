#include "editor_client/window/frame_presenter.h"

#include <chrono>
#include <thread>
#include <utility>

#include "editor_client/vk/vk_result.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

Result<std::unique_ptr<FramePresenter>> FramePresenter::create(const vk::Context& context, Window& window,
                                                               bool panels) {
    const vk::Device& device = context.device();
    Result<VkCommandBuffer> cmd = context.command_pool().allocate();
    if (!cmd) return make_error(cmd.error());
    Result<vk::Fence> frame_done = vk::Fence::create(device.handle());
    if (!frame_done) return make_error(frame_done.error());
    Result<vk::Semaphore> image_ready = vk::Semaphore::create(device.handle());
    if (!image_ready) return make_error(image_ready.error());
    GlfwWindow* glfw = panels ? dynamic_cast<GlfwWindow*>(&window) : nullptr;
    return std::unique_ptr<FramePresenter>(new FramePresenter(
        context, window, glfw, *cmd, std::move(frame_done).value(), std::move(image_ready).value()));
}

FramePresenter::FramePresenter(const vk::Context& context, Window& window, GlfwWindow* glfw,
                               VkCommandBuffer cmd, vk::Fence frame_done, vk::Semaphore image_ready)
    : context_(context),
      window_(window),
      glfw_(glfw),
      presenting_(window.has_surface()),
      cmd_(cmd),
      frame_done_(std::move(frame_done)),
      image_ready_(std::move(image_ready)),
      recreate_(presenting_) {}

Result<bool> FramePresenter::acquire() {
    if (!presenting_) return true;
    const VkExtent2D extent = window_.framebuffer_size();
    if (extent.width == 0 || extent.height == 0) {  // minimised: nothing to show
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return false;
    }
    Result<bool> remade = ensure_presentation(context_, extent, presentation_, recreate_);
    if (!remade) return make_error(remade.error());
    if (*remade) LC_RETURN_IF_ERROR(remake_ui());
    Result<bool> stale = acquire_image(*presentation_, image_ready_, image_index_);
    if (!stale) return make_error(stale.error());
    if (*stale) {
        recreate_ = true;
        return false;
    }
    return true;
}

Status FramePresenter::remake_ui() {
    if (glfw_ != nullptr && !ui_) {
        Result<std::unique_ptr<ImGuiLayer>> layer = ImGuiLayer::create(glfw_->handle(), context_);
        if (!layer) return make_error("editor panels: " + layer.error());
        ui_ = std::move(layer).value();
    }
    if (ui_) LC_RETURN_IF_ERROR(ui_->resize(presentation_->swapchain.extent()));
    return Ok{};
}

Result<VkCommandBuffer> FramePresenter::begin() {
    LC_RETURN_IF_ERROR(begin_frame_commands(cmd_));
    return cmd_;
}

Status FramePresenter::present(const Status& recorded, const vk::Image& shown, DisplayWrite written) {
    const bool draw_panels = ui_ && ui_->frame_open() && recorded && presenting_;
    if (recorded && presenting_) {
        const VkImage target = presentation_->swapchain.images()[image_index_];
        if (draw_panels) {
            record_blit(cmd_, shown, ui_->composite().handle(), presentation_->swapchain.extent(), true,
                        written);
            ui_->record(cmd_, target);
        } else {
            record_blit(cmd_, shown, target, presentation_->swapchain.extent(), false, written);
        }
    }
    LC_VK_CHECK(vkEndCommandBuffer(cmd_));
    const vk::Device& device = context_.device();
    if (!recorded) {
        LC_RETURN_IF_ERROR(device.wait_idle());
        return make_error(recorded.error());
    }
    Result<bool> out_of_date = submit_and_present(device, presenting_ ? &*presentation_ : nullptr, cmd_,
                                                  image_ready_, image_index_, frame_done_);
    if (!out_of_date) return make_error(out_of_date.error());
    if (*out_of_date) recreate_ = true;
    return Ok{};
}

}  // namespace lc::client
