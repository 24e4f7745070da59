#pragma once
// Dear ImGui drawn over the editor's view: the GLFW and Vulkan backends and a
// composite image the size of the window. The view is blitted into the
// composite, the panels are drawn over it, and the composite is copied to the
// swapchain image (which is only a transfer destination). The composite stays
// readable afterwards: a screenshot of the window with its panels.
#include <vulkan/vulkan.h>

#include <memory>
#include <vector>

#include "editor_client/vk/context.h"
#include "editor_client/vk/device_handle.h"
#include "editor_client/vk/image.h"
#include "lightcuts/result.h"

struct GLFWwindow;

namespace lc::client {

class ImGuiLayer {
public:
    // One ImGui context per process: a second layer at once is refused.
    static Result<std::unique_ptr<ImGuiLayer>> create(GLFWwindow* window, const vk::Context& context);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    // Call whenever the swapchain was (re)created: sizes the composite.
    Status resize(VkExtent2D extent);
    // Where the view is blitted to (then COLOR_ATTACHMENT_OPTIMAL for record()).
    const vk::Image& composite() const { return composite_; }
    // Ends a frame that begin_frame() opened but no record() drew (a skipped
    // frame); does nothing otherwise.
    void discard_open_frame();
    bool frame_open() const { return frame_open_; }
    // Starts an ImGui frame (then draw panels with ImGui calls).
    void begin_frame();
    // Ends the ImGui frame, draws it over the composite (which must be in
    // COLOR_ATTACHMENT_OPTIMAL and ends in TRANSFER_SRC_OPTIMAL) and copies the
    // composite to `swapchain_image`, left in PRESENT_SRC_KHR.
    void record(VkCommandBuffer cmd, VkImage swapchain_image);
    // The last recorded composite as RGBA8, rows top to bottom (GPU idle).
    Result<std::vector<uint8_t>> read_composite() const;
    // Whether the panels take the mouse or keyboard this frame.
    bool wants_mouse() const;
    bool wants_keyboard() const;

private:
    explicit ImGuiLayer(const vk::Context& context) : context_(context) {}
    Status create_render_pass(VkDevice device);
    Status create_descriptor_pool(VkDevice device);
    Status init_backends(GLFWwindow* window);

    const vk::Context& context_;
    // Destroyed after the destructor has shut ImGui's Vulkan backend down,
    // in reverse order: the framebuffer, the composite, the pool, the pass.
    vk::DeviceHandle<VkRenderPass> render_pass_;
    vk::DeviceHandle<VkDescriptorPool> descriptor_pool_;
    vk::Image composite_;
    vk::DeviceHandle<VkFramebuffer> framebuffer_;
    VkExtent2D extent_{0, 0};
    bool drawn_ = false;  // the composite holds a finished frame
    bool glfw_ready_ = false;
    bool vulkan_ready_ = false;
    bool frame_open_ = false;
};

}  // namespace lc::client
