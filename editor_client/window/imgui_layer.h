#pragma once
// Dear ImGui drawn over the editor's swapchain image: the GLFW and Vulkan
// backends, a render pass that loads the blitted view and ends ready to
// present, and one framebuffer per swapchain image (rebuilt with it).
#include <vulkan/vulkan.h>

#include <memory>
#include <vector>

#include "editor_client/vk/context.h"
#include "editor_client/vk/swapchain.h"
#include "protocol/result.h"

struct GLFWwindow;

namespace lc::client {

class ImGuiLayer {
public:
    // One ImGui context per process: a second layer at once is refused.
    static Result<std::unique_ptr<ImGuiLayer>> create(GLFWwindow* window,
                                                      const vk::Context& context,
                                                      VkFormat swapchain_format);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    // Call whenever the swapchain was (re)created, before recording into it.
    Status attach(const vk::Swapchain& swapchain);
    // Ends a frame that begin_frame() opened but no record() drew (a skipped
    // frame); does nothing otherwise.
    void discard_open_frame();
    bool frame_open() const { return frame_open_; }
    // Starts an ImGui frame (then draw panels with ImGui calls).
    void begin_frame();
    // Ends the ImGui frame and records its draw into swapchain image
    // `image_index`, which must be in COLOR_ATTACHMENT_OPTIMAL; it ends in
    // PRESENT_SRC_KHR.
    void record(VkCommandBuffer cmd, uint32_t image_index);
    // Whether the panels take the mouse or keyboard this frame.
    bool wants_mouse() const;
    bool wants_keyboard() const;

private:
    explicit ImGuiLayer(const vk::Context& context) : context_(context) {}
    void destroy_framebuffers();

    const vk::Context& context_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
    std::vector<VkImageView> views_;
    std::vector<VkFramebuffer> framebuffers_;
    VkExtent2D extent_{0, 0};
    bool glfw_ready_ = false;
    bool vulkan_ready_ = false;
    bool frame_open_ = false;
};

}  // namespace lc::client
