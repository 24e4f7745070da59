#include "editor_client/vk/sync.h"

#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<Fence> Fence::create(VkDevice device, bool signaled) {
    VkFenceCreateInfo info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    if (signaled) info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkFence handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateFence(device, &info, nullptr, &handle));
    Fence fence;
    fence.fence_ = DeviceHandle<VkFence>(device, handle, vkDestroyFence);
    return fence;
}

Status Fence::wait_and_reset(uint64_t timeout_ns) const {
    VkFence handle = fence_.get();
    LC_VK_CHECK(vkWaitForFences(fence_.device(), 1, &handle, VK_TRUE, timeout_ns));
    LC_VK_CHECK(vkResetFences(fence_.device(), 1, &handle));
    return Ok{};
}

Result<Semaphore> Semaphore::create(VkDevice device) {
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateSemaphore(device, &info, nullptr, &handle));
    Semaphore semaphore;
    semaphore.semaphore_ = DeviceHandle<VkSemaphore>(device, handle, vkDestroySemaphore);
    return semaphore;
}

}  // namespace lc::vk
