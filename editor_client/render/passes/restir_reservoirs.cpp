#include "editor_client/render/passes/restir_reservoirs.h"

#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/device/restir.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

static_assert(sizeof(GpuReservoir) == 48, "GpuReservoir must match its std430 layout");

Result<RestirReservoirs> RestirReservoirs::create(const vk::Device& device) {
    RestirReservoirs reservoirs(device);
    std::array<VkDescriptorType, kRestirBindingCount> types{};
    types.fill(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    Result<vk::DescriptorSetLayout> layout =
        vk::DescriptorSetLayout::create(device.handle(), types, VK_SHADER_STAGE_COMPUTE_BIT);
    if (!layout) return make_error(layout.error());
    reservoirs.set_layout_ = std::move(layout).value();
    const std::array<VkDescriptorPoolSize, 1> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * kRestirBindingCount}};
    Result<vk::DescriptorPool> pool = vk::DescriptorPool::create(device.handle(), 2, sizes);
    if (!pool) return make_error(pool.error());
    reservoirs.pool_ = std::move(pool).value();
    for (VkDescriptorSet& set : reservoirs.sets_) {
        Result<VkDescriptorSet> allocated = reservoirs.pool_.allocate(reservoirs.set_layout_);
        if (!allocated) return make_error(allocated.error());
        set = *allocated;
    }
    return reservoirs;
}

Status RestirReservoirs::prepare(uint32_t width, uint32_t height) {
    if (width == width_ && height == height_) return Ok{};
    // The old buffers may be in a frame still in flight.
    LC_RETURN_IF_ERROR(device_->wait_idle());
    const VkDeviceSize bytes = VkDeviceSize(width) * height * sizeof(GpuReservoir);
    for (vk::Buffer& buffer : buffers_) {
        Result<vk::Buffer> made = vk::Buffer::create(*device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                     vk::MemoryUsage::kDeviceLocal);
        if (!made) return make_error("ReSTIR reservoirs: " + made.error());
        buffer = std::move(made).value();
    }
    width_ = width;
    height_ = height;
    bind_sets();
    return Ok{};
}

// Set p reads buffer p as the previous frame's and writes buffer 1 - p as this frame's.
void RestirReservoirs::bind_sets() {
    for (uint32_t p = 0; p < 2; ++p) {
        vk::DescriptorWriter(sets_[p])
            .storage_buffer(kBindReservoirsPrevious, buffers_[p].handle())
            .storage_buffer(kBindReservoirsTemporal, buffers_[2].handle())
            .storage_buffer(kBindReservoirsFinal, buffers_[1 - p].handle())
            .update(device_->handle());
    }
}

}  // namespace lc::client
