#pragma once
// The editor's present step: one frame's command buffer, its fence and
// acquire semaphore, the swapchain (remade when the window's size changes or
// it goes out of date) and the ImGui layer that draws the panels over the
// view. Headless, frames are recorded and submitted but never presented.
#include <vulkan/vulkan.h>

#include <memory>
#include <optional>

#include "editor_client/vk/context.h"
#include "editor_client/vk/image.h"
#include "editor_client/vk/sync.h"
#include "editor_client/window/glfw_window.h"
#include "editor_client/window/imgui_layer.h"
#include "editor_client/window/presentation.h"
#include "editor_client/window/window.h"
#include "lightcuts/result.h"

namespace lc::client {

class FramePresenter {
public:
    // `panels`: draw the ImGui panels (a GlfwWindow only; ignored otherwise).
    static Result<std::unique_ptr<FramePresenter>> create(const vk::Context& context, Window& window,
                                                          bool panels);

    // A swapchain image to draw into, made when the swapchain is (re)made with
    // the ImGui layer sized to it. False: skip this frame (the window is
    // minimised, or the swapchain was out of date and is remade next frame).
    Result<bool> acquire();
    // Begins the frame's command buffer, for the render step to record into.
    Result<VkCommandBuffer> begin();
    // Scales `shown` onto the swapchain image (the panels drawn over it), ends
    // the commands and submits them, presenting the image. A failed recording
    // (`recorded`) submits nothing and is returned once the GPU is idle.
    Status present(const Status& recorded, const vk::Image& shown, DisplayWrite written);

    // Null until the first swapchain (the layer needs its format), and without panels.
    ImGuiLayer* ui() const { return ui_.get(); }
    GlfwWindow* glfw() const { return glfw_; }

private:
    FramePresenter(const vk::Context& context, Window& window, GlfwWindow* glfw, VkCommandBuffer cmd,
                   vk::Fence frame_done, vk::Semaphore image_ready);
    Status remake_ui();

    const vk::Context& context_;
    Window& window_;
    GlfwWindow* glfw_;  // the window when it draws panels
    bool presenting_;
    VkCommandBuffer cmd_;
    vk::Fence frame_done_;
    vk::Semaphore image_ready_;
    std::optional<Presentation> presentation_;
    bool recreate_;
    uint32_t image_index_ = 0;
    std::unique_ptr<ImGuiLayer> ui_;
};

}  // namespace lc::client
