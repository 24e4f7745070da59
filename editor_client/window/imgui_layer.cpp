#include "editor_client/window/imgui_layer.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <atomic>

#include "editor_client/vk/barriers.h"
#include "editor_client/vk/vk_result.h"

namespace lc::client {
namespace {

std::atomic<bool> g_layer_exists{false};
// 8-bit like the renderer's display image, so the blits copy values unchanged.
constexpr VkFormat kCompositeFormat = VK_FORMAT_R8G8B8A8_UNORM;

void check_imgui_vk(VkResult result) {
    // The backend has no error channel; a failure here is logged by the
    // validation layer when enabled, and shows as a missing panel.
    (void)result;
}

}  // namespace

Result<std::unique_ptr<ImGuiLayer>> ImGuiLayer::create(GLFWwindow* window, const vk::Context& context) {
    if (window == nullptr) return make_error("the editor panels need a GLFW window");
    if (g_layer_exists.exchange(true)) return make_error("an ImGui layer already exists");
    std::unique_ptr<ImGuiLayer> layer(new ImGuiLayer(context));
    const VkDevice device = context.device().handle();
    LC_RETURN_IF_ERROR(layer->create_render_pass(device));
    LC_RETURN_IF_ERROR(layer->create_descriptor_pool(device));
    LC_RETURN_IF_ERROR(layer->init_backends(window));
    return layer;
}

// One pass that draws the panels over the blitted view, then hands the
// composite to the copy into the swapchain.
Status ImGuiLayer::create_render_pass(VkDevice device) {
    VkAttachmentDescription colour{};
    colour.format = kCompositeFormat;
    colour.samples = VK_SAMPLE_COUNT_1_BIT;
    colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the blitted view stays under the panels
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    colour.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colour.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    VkSubpassDependency dependency{};
    dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
    dependency.dstSubpass = 0;
    dependency.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependency.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependency.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    // The copy to the swapchain waits for the panels' writes.
    VkSubpassDependency to_copy{};
    to_copy.srcSubpass = 0;
    to_copy.dstSubpass = VK_SUBPASS_EXTERNAL;
    to_copy.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    to_copy.dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    to_copy.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    to_copy.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    const VkSubpassDependency dependencies[] = {dependency, to_copy};
    VkRenderPassCreateInfo pass_info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    pass_info.attachmentCount = 1;
    pass_info.pAttachments = &colour;
    pass_info.subpassCount = 1;
    pass_info.pSubpasses = &subpass;
    pass_info.dependencyCount = 2;
    pass_info.pDependencies = dependencies;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateRenderPass(device, &pass_info, nullptr, &render_pass));
    render_pass_ = vk::DeviceHandle<VkRenderPass>(device, render_pass, vkDestroyRenderPass);
    return Ok{};
}

// The font atlas is the backend's only descriptor set.
Status ImGuiLayer::create_descriptor_pool(VkDevice device) {
    VkDescriptorPoolSize sizes{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pool_info.maxSets = 4;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &sizes;
    VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateDescriptorPool(device, &pool_info, nullptr, &descriptor_pool));
    descriptor_pool_ = vk::DeviceHandle<VkDescriptorPool>(device, descriptor_pool, vkDestroyDescriptorPool);
    return Ok{};
}

// ImGui's context, its GLFW and Vulkan backends, and the font atlas uploaded.
Status ImGuiLayer::init_backends(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // deterministic layout, no file left behind
    ImGui::StyleColorsDark();
    // Installed after GlfwWindow's callbacks, so ImGui chains to them.
    if (!ImGui_ImplGlfw_InitForVulkan(window, true))
        return make_error("ImGui could not attach to the GLFW window");
    glfw_ready_ = true;

    ImGui_ImplVulkan_InitInfo init{};
    init.Instance = context_.instance().handle();
    init.PhysicalDevice = context_.physical().handle;
    init.Device = context_.device().handle();
    init.QueueFamily = context_.device().queue_family();
    init.Queue = context_.device().queue();
    init.DescriptorPool = descriptor_pool_.get();
    init.MinImageCount = 2;
    init.ImageCount = 3;
    init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    init.CheckVkResultFn = &check_imgui_vk;
    if (!ImGui_ImplVulkan_Init(&init, render_pass_.get()))
        return make_error("ImGui's Vulkan backend failed to initialise");
    vulkan_ready_ = true;
    LC_RETURN_IF_ERROR(context_.command_pool().run_one_time(
        context_.device(), [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); }));
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    return Ok{};
}

ImGuiLayer::~ImGuiLayer() {
    const VkDevice device = context_.device().handle();
    vkDeviceWaitIdle(device);
    if (frame_open_) ImGui::EndFrame();
    if (vulkan_ready_) ImGui_ImplVulkan_Shutdown();
    if (glfw_ready_) ImGui_ImplGlfw_Shutdown();
    if (ImGui::GetCurrentContext() != nullptr) ImGui::DestroyContext();
    g_layer_exists.store(false);
}

Status ImGuiLayer::resize(VkExtent2D extent) {
    if (extent.width == extent_.width && extent.height == extent_.height && framebuffer_) return Ok{};
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    framebuffer_.reset();
    drawn_ = false;
    vk::ImageDesc desc;
    desc.width = extent.width;
    desc.height = extent.height;
    desc.format = kCompositeFormat;
    desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                 VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    Result<vk::Image> image = vk::Image::create(context_.device(), desc);
    if (!image) return make_error("editor panels: " + image.error());
    composite_ = std::move(image).value();
    extent_ = extent;
    VkImageView view = composite_.view();
    VkFramebufferCreateInfo fb_info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fb_info.renderPass = render_pass_.get();
    fb_info.attachmentCount = 1;
    fb_info.pAttachments = &view;
    fb_info.width = extent_.width;
    fb_info.height = extent_.height;
    fb_info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateFramebuffer(context_.device().handle(), &fb_info, nullptr, &framebuffer));
    framebuffer_ = vk::DeviceHandle<VkFramebuffer>(context_.device().handle(), framebuffer, vkDestroyFramebuffer);
    ImGui_ImplVulkan_SetMinImageCount(2);
    return Ok{};
}

void ImGuiLayer::discard_open_frame() {
    if (frame_open_) ImGui::EndFrame();
    frame_open_ = false;
}

void ImGuiLayer::begin_frame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    frame_open_ = true;
}

void ImGuiLayer::record(VkCommandBuffer cmd, VkImage swapchain_image) {
    ImGui::Render();
    frame_open_ = false;
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = render_pass_.get();
    begin.framebuffer = framebuffer_.get();
    begin.renderArea.extent = extent_;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);

    vk::transition_image(
        cmd, {swapchain_image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
              VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT});
    VkImageBlit region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {int32_t(extent_.width), int32_t(extent_.height), 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstOffsets[1] = {int32_t(extent_.width), int32_t(extent_.height), 1};
    // A blit, not a copy: it converts to the swapchain's format (BGRA, sRGB).
    vkCmdBlitImage(cmd, composite_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchain_image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_NEAREST);
    vk::transition_image(
        cmd, {swapchain_image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
              VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, 0});
    drawn_ = true;
}

Result<std::vector<uint8_t>> ImGuiLayer::read_composite() const {
    if (!drawn_) return make_error("no window frame was drawn, so no window screenshot");
    Result<std::vector<std::byte>> bytes = vk::read_back_image(
        context_.device(), context_.command_pool(), composite_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    if (!bytes) return make_error(bytes.error());
    std::vector<uint8_t> out(bytes->size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = uint8_t(bytes.value()[i]);
    return out;
}

bool ImGuiLayer::wants_mouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}
bool ImGuiLayer::wants_keyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

}  // namespace lc::client
