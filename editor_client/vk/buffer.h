#pragma once
// A VkBuffer with its own memory. Host-visible buffers stay mapped; device
// buffers are filled through a staging copy and read back the same way.
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

enum class MemoryUsage {
    kDeviceLocal,   // GPU only; filled by staging copies
    kHostUpload,    // CPU writes, GPU reads (staging, per-frame data)
    kHostReadback,  // GPU writes, CPU reads (cached when possible)
};

class Buffer {
public:
    static Result<Buffer> create(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage,
                                 MemoryUsage memory);
    // A device-local buffer holding `bytes` (at least 1 byte is allocated so
    // empty arrays still bind). Waits for the copy.
    static Result<Buffer> create_with_data(const Device& device, const CommandPool& pool,
                                           std::span<const std::byte> bytes,
                                           VkBufferUsageFlags usage);

    Buffer() = default;
    Buffer(Buffer&&) noexcept = default;
    Buffer& operator=(Buffer&&) noexcept = default;
    ~Buffer();

    VkBuffer handle() const { return buffer_.get(); }
    VkDeviceSize size() const { return size_; }
    // Non-null for host-visible buffers.
    void* mapped() const { return mapped_; }
    explicit operator bool() const { return static_cast<bool>(buffer_); }

    // Copies `bytes` to offset 0 of a host-visible buffer.
    Status write(std::span<const std::byte> bytes) const;
    // Copies the whole of a device buffer back to the CPU (staging + wait).
    Result<std::vector<std::byte>> read_back(const Device& device, const CommandPool& pool) const;

private:
    // Declared before buffer_ so the buffer is destroyed first.
    DeviceHandle<VkDeviceMemory> memory_;
    DeviceHandle<VkBuffer> buffer_;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

}  // namespace lc::vk
