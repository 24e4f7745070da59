#include "editor_client/vk/buffer.h"

#include <algorithm>
#include <cstring>

#include "editor_client/vk/barriers.h"
#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<Buffer> Buffer::create(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage,
                              MemoryUsage memory) {
    Buffer result;
    result.size_ = std::max<VkDeviceSize>(size, 4);
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = result.size_;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateBuffer(device.handle(), &info, nullptr, &buffer));
    result.buffer_ = DeviceHandle<VkBuffer>(device.handle(), buffer, vkDestroyBuffer);

    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device.handle(), buffer, &requirements);
    VkMemoryPropertyFlags required = 0;
    VkMemoryPropertyFlags preferred = 0;
    switch (memory) {
        case MemoryUsage::kDeviceLocal:
            required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
            break;
        case MemoryUsage::kHostUpload:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            break;
        case MemoryUsage::kHostReadback:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
            break;
    }
    std::optional<uint32_t> type =
        device.find_memory_type(requirements.memoryTypeBits, required, preferred);
    if (!type)
        return make_error("no Vulkan memory type fits a buffer of " + std::to_string(size) +
                          " bytes");

    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = requirements.size;
    alloc.memoryTypeIndex = *type;
    VkDeviceMemory memory_handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkAllocateMemory(device.handle(), &alloc, nullptr, &memory_handle));
    result.memory_ = DeviceHandle<VkDeviceMemory>(device.handle(), memory_handle, vkFreeMemory);
    LC_VK_CHECK(vkBindBufferMemory(device.handle(), buffer, memory_handle, 0));
    if (memory != MemoryUsage::kDeviceLocal)
        LC_VK_CHECK(
            vkMapMemory(device.handle(), memory_handle, 0, VK_WHOLE_SIZE, 0, &result.mapped_));
    return result;
}

Buffer::~Buffer() {
    if (mapped_ != nullptr && memory_) vkUnmapMemory(memory_.device(), memory_.get());
}

Result<Buffer> Buffer::create_with_data(const Device& device, const CommandPool& pool,
                                        std::span<const std::byte> bytes,
                                        VkBufferUsageFlags usage) {
    Result<Buffer> staging =
        create(device, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::kHostUpload);
    if (!staging) return make_error(staging.error());
    LC_RETURN_IF_ERROR(staging->write(bytes));
    Result<Buffer> target = create(device, bytes.size(), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                   MemoryUsage::kDeviceLocal);
    if (!target) return make_error(target.error());
    VkBufferCopy region{0, 0, staging->size()};
    VkBuffer src = staging->handle();
    VkBuffer dst = target->handle();
    LC_RETURN_IF_ERROR(pool.run_one_time(
        device, [&](VkCommandBuffer cmd) { vkCmdCopyBuffer(cmd, src, dst, 1, &region); }));
    return std::move(target).value();
}

Status Buffer::write(std::span<const std::byte> bytes) const {
    if (mapped_ == nullptr) return make_error("Buffer::write on a buffer that is not host-visible");
    if (bytes.size() > size_)
        return make_error("Buffer::write of " + std::to_string(bytes.size()) +
                          " bytes into a buffer of " + std::to_string(size_));
    if (!bytes.empty()) std::memcpy(mapped_, bytes.data(), bytes.size());
    return Ok{};
}

Result<std::vector<std::byte>> Buffer::read_back(const Device& device,
                                                 const CommandPool& pool) const {
    std::vector<std::byte> out(size_);
    if (mapped_ != nullptr) {
        std::memcpy(out.data(), mapped_, size_);
        return out;
    }
    Result<Buffer> staging =
        create(device, size_, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::kHostReadback);
    if (!staging) return make_error(staging.error());
    VkBufferCopy region{0, 0, size_};
    VkBuffer src = buffer_.get();
    VkBuffer dst = staging->handle();
    LC_RETURN_IF_ERROR(pool.run_one_time(device, [&](VkCommandBuffer cmd) {
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        vkCmdCopyBuffer(cmd, src, dst, 1, &region);
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    }));
    std::memcpy(out.data(), staging->mapped(), size_);
    return out;
}

}  // namespace lc::vk
