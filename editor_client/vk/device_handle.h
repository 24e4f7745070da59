#pragma once
// A move-only owner of one handle created from a VkDevice (buffer, image view,
// pipeline, ...). It calls the matching vkDestroy*/vkFree* exactly once, so the
// code above editor_client/vk/ never destroys anything by hand.
#include <vulkan/vulkan.h>

#include <utility>

namespace lc::vk {

template <typename Handle>
class DeviceHandle {
public:
    using DestroyFn = void (*)(VkDevice, Handle, const VkAllocationCallbacks*);

    DeviceHandle() = default;
    DeviceHandle(VkDevice device, Handle handle, DestroyFn destroy)
        : device_(device), handle_(handle), destroy_(destroy) {}
    ~DeviceHandle() { reset(); }

    DeviceHandle(const DeviceHandle&) = delete;
    DeviceHandle& operator=(const DeviceHandle&) = delete;
    DeviceHandle(DeviceHandle&& other) noexcept { *this = std::move(other); }
    DeviceHandle& operator=(DeviceHandle&& other) noexcept {
        if (this != &other) {
            reset();
            device_ = std::exchange(other.device_, VK_NULL_HANDLE);
            handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
            destroy_ = std::exchange(other.destroy_, nullptr);
        }
        return *this;
    }

    Handle get() const { return handle_; }
    VkDevice device() const { return device_; }
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

    void reset() {
        if (handle_ != VK_NULL_HANDLE && destroy_ != nullptr) destroy_(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    Handle handle_ = VK_NULL_HANDLE;
    DestroyFn destroy_ = nullptr;
};

}  // namespace lc::vk
