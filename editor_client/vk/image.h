#pragma once
// A 2D VkImage with its own memory and one view over all of it.
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "editor_client/vk/command_pool.h"
#include "editor_client/vk/device.h"
#include "editor_client/vk/device_handle.h"
#include "lightcuts/result.h"

namespace lc::vk {

struct ImageDesc {
    uint32_t width = 1;
    uint32_t height = 1;
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    VkImageUsageFlags usage = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
};

class Image {
public:
    static Result<Image> create(const Device& device, const ImageDesc& desc);

    VkImage handle() const { return image_.get(); }
    VkImageView view() const { return view_.get(); }
    const ImageDesc& desc() const { return desc_; }
    VkExtent2D extent() const { return {desc_.width, desc_.height}; }
    explicit operator bool() const { return static_cast<bool>(image_); }

private:
    // Destroyed in reverse order: view, image, then memory.
    DeviceHandle<VkDeviceMemory> memory_;
    DeviceHandle<VkImage> image_;
    DeviceHandle<VkImageView> view_;
    ImageDesc desc_;
};

// Bytes per texel of the formats we upload and read back (0 for others).
uint32_t bytes_per_texel(VkFormat format);

// Fills a whole image from tightly packed texels (staging copy, waits) and
// leaves it in `final_layout`.
Status upload_image(const Device& device, const CommandPool& pool, const Image& image,
                    std::span<const std::byte> texels, VkImageLayout final_layout);

// Copies a whole image, currently in `layout` (which it keeps), to tightly
// packed texels, rows top to bottom (staging copy, waits).
Result<std::vector<std::byte>> read_back_image(const Device& device, const CommandPool& pool,
                                               const Image& image, VkImageLayout layout);

}  // namespace lc::vk
