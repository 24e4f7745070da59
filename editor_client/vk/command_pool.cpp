#include "editor_client/vk/command_pool.h"

#include "editor_client/vk/sync.h"
#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<CommandPool> CommandPool::create(const Device& device) {
    VkCommandPoolCreateInfo info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    info.queueFamilyIndex = device.queue_family();
    VkCommandPool handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateCommandPool(device.handle(), &info, nullptr, &handle));
    CommandPool pool;
    pool.pool_ = DeviceHandle<VkCommandPool>(device.handle(), handle, vkDestroyCommandPool);
    return pool;
}

Result<VkCommandBuffer> CommandPool::allocate() const {
    VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    info.commandPool = pool_.get();
    info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    info.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    LC_VK_CHECK(vkAllocateCommandBuffers(pool_.device(), &info, &cmd));
    return cmd;
}

Status CommandPool::run_one_time(const Device& device,
                                 const std::function<void(VkCommandBuffer)>& record) const {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    LC_VK_CHECK(vkAllocateCommandBuffers(device.handle(), &alloc, &cmd));
    // Frees the command buffer on every path out of this function.
    struct FreeOnExit {
        VkDevice device;
        VkCommandPool pool;
        VkCommandBuffer cmd;
        ~FreeOnExit() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
    } free_on_exit{device.handle(), pool_.get(), cmd};

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    LC_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    LC_VK_CHECK(vkEndCommandBuffer(cmd));

    Result<Fence> fence = Fence::create(device.handle());
    if (!fence) return make_error(fence.error());
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    LC_VK_CHECK(vkQueueSubmit(device.queue(), 1, &submit, fence->handle()));
    Status waited = fence->wait_and_reset();
    // Never free a command buffer the GPU may still be reading.
    if (!waited) vkDeviceWaitIdle(device.handle());
    return waited;
}

}  // namespace lc::vk
