#include "editor_client/vk/image.h"

#include <cstring>
#include <string>

#include "editor_client/vk/barriers.h"
#include "editor_client/vk/buffer.h"
#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<Image> Image::create(const Device& device, const ImageDesc& desc) {
    if (desc.width == 0 || desc.height == 0)
        return make_error("image size " + std::to_string(desc.width) + "x" +
                          std::to_string(desc.height) + " is empty");
    Image result;
    result.desc_ = desc;

    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = {desc.width, desc.height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = desc.usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateImage(device.handle(), &info, nullptr, &image));
    result.image_ = DeviceHandle<VkImage>(device.handle(), image, vkDestroyImage);

    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device.handle(), image, &requirements);
    std::optional<uint32_t> type =
        device.find_memory_type(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (!type) return make_error("no device-local Vulkan memory type fits the image");
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = requirements.size;
    alloc.memoryTypeIndex = *type;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    LC_VK_CHECK(vkAllocateMemory(device.handle(), &alloc, nullptr, &memory));
    result.memory_ = DeviceHandle<VkDeviceMemory>(device.handle(), memory, vkFreeMemory);
    LC_VK_CHECK(vkBindImageMemory(device.handle(), image, memory, 0));

    VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view_info.image = image;
    view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = desc.format;
    view_info.subresourceRange = {desc.aspect, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateImageView(device.handle(), &view_info, nullptr, &view));
    result.view_ = DeviceHandle<VkImageView>(device.handle(), view, vkDestroyImageView);
    return result;
}

uint32_t bytes_per_texel(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_R8G8B8A8_SRGB:
        case VK_FORMAT_B8G8R8A8_UNORM:
        case VK_FORMAT_B8G8R8A8_SRGB:
        case VK_FORMAT_R32_UINT:
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_D32_SFLOAT:
            return 4;
        case VK_FORMAT_R32G32_UINT:
        case VK_FORMAT_R16G16B16A16_SFLOAT:
            return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT:
        case VK_FORMAT_R32G32B32A32_UINT:
            return 16;
        default:
            return 0;
    }
}

Status upload_image(const Device& device, const CommandPool& pool, const Image& image,
                    std::span<const std::byte> texels, VkImageLayout final_layout) {
    const ImageDesc& desc = image.desc();
    size_t expected = size_t(desc.width) * desc.height * bytes_per_texel(desc.format);
    if (expected == 0 || texels.size() != expected)
        return make_error("upload_image: got " + std::to_string(texels.size()) + " bytes for a " +
                          std::to_string(desc.width) + "x" + std::to_string(desc.height) +
                          " image that needs " + std::to_string(expected));
    Result<Buffer> staging = Buffer::create(device, texels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                            MemoryUsage::kHostUpload);
    if (!staging) return make_error(staging.error());
    LC_RETURN_IF_ERROR(staging->write(texels));
    VkBuffer src = staging->handle();
    return pool.run_one_time(device, [&](VkCommandBuffer cmd) {
        transition_image(
            cmd, {image.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT, desc.aspect});
        VkBufferImageCopy region{};
        region.imageSubresource = {desc.aspect, 0, 0, 1};
        region.imageExtent = {desc.width, desc.height, 1};
        vkCmdCopyBufferToImage(cmd, src, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &region);
        transition_image(
            cmd, {image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, final_layout,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT, desc.aspect});
    });
}

Result<std::vector<std::byte>> read_back_image(const Device& device, const CommandPool& pool,
                                               const Image& image, VkImageLayout layout) {
    const ImageDesc& desc = image.desc();
    size_t size = size_t(desc.width) * desc.height * bytes_per_texel(desc.format);
    if (size == 0) return make_error("read_back_image: unsupported image format");
    Result<Buffer> staging =
        Buffer::create(device, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::kHostReadback);
    if (!staging) return make_error(staging.error());
    VkBuffer dst = staging->handle();
    LC_RETURN_IF_ERROR(pool.run_one_time(device, [&](VkCommandBuffer cmd) {
        transition_image(
            cmd, {image.handle(), layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, desc.aspect});
        VkBufferImageCopy region{};
        region.imageSubresource = {desc.aspect, 0, 0, 1};
        region.imageExtent = {desc.width, desc.height, 1};
        vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, 1,
                               &region);
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        transition_image(cmd, {image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
                               VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                               VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, desc.aspect});
    }));
    std::vector<std::byte> texels(size);
    std::memcpy(texels.data(), staging->mapped(), size);
    return texels;
}

}  // namespace lc::vk
