#include "editor_client/render/passes/reconstruction_records.h"

#include <array>
#include <span>
#include <string>
#include <tuple>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/gpu_structs.h"

namespace lc::client {

namespace {

// GpuCutRecords per sample: four records each, the cap rounded up.
uint64_t record_words(uint32_t cap) { return (uint64_t(cap) + 3) / 4; }

}  // namespace

uint32_t reconstruction_lattice_side(uint32_t side, uint32_t block) {
    return (side + block - 2) / block + 1;
}

uint64_t reconstruction_bytes(uint32_t width, uint32_t height, uint32_t block, uint32_t cap) {
    const uint64_t samples =
        uint64_t(reconstruction_lattice_side(width, block)) * reconstruction_lattice_side(height, block);
    return samples * (sizeof(GpuReconstructionSample) + record_words(cap) * sizeof(GpuCutRecords));
}

Result<ReconstructionRecords> ReconstructionRecords::create(const vk::Device& device) {
    ReconstructionRecords records(device);
    static_assert(kBindReconstructionSamples == 0u && kBindReconstructionRecords == 1u);
    const std::array<VkDescriptorType, kReconstructionBindingCount> types{
        VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    Result<vk::DescriptorSetLayout> layout =
        vk::DescriptorSetLayout::create(device.handle(), types, VK_SHADER_STAGE_COMPUTE_BIT);
    if (!layout) return make_error(layout.error());
    records.set_layout_ = std::move(layout).value();
    const std::array<VkDescriptorPoolSize, 1> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kReconstructionBindingCount}};
    Result<vk::DescriptorPool> pool = vk::DescriptorPool::create(device.handle(), 1, sizes);
    if (!pool) return make_error(pool.error());
    records.pool_ = std::move(pool).value();
    Result<VkDescriptorSet> allocated = records.pool_.allocate(records.set_layout_);
    if (!allocated) return make_error(allocated.error());
    records.set_ = *allocated;
    return records;
}

Status ReconstructionRecords::reserve(uint32_t width, uint32_t height, uint32_t block, uint32_t cap) {
    const uint64_t samples =
        uint64_t(reconstruction_lattice_side(width, block)) * reconstruction_lattice_side(height, block);
    const VkDeviceSize header_bytes = samples * sizeof(GpuReconstructionSample);
    const VkDeviceSize record_bytes = samples * record_words(cap) * sizeof(GpuCutRecords);
    if (samples_ && records_ && samples_.size() >= header_bytes && records_.size() >= record_bytes)
        return Ok{};
    for (auto [buffer, bytes, what] : {std::tuple{&samples_, header_bytes, "samples"},
                                       std::tuple{&records_, record_bytes, "records"}}) {
        Result<vk::Buffer> made = vk::Buffer::create(*device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                     vk::MemoryUsage::kDeviceLocal);
        if (!made)
            return make_error(std::string("reconstruction ") + what + " (" + std::to_string(bytes) +
                              " bytes): " + made.error());
        *buffer = std::move(made).value();
    }
    vk::DescriptorWriter(set_)
        .storage_buffer(kBindReconstructionSamples, samples_.handle())
        .storage_buffer(kBindReconstructionRecords, records_.handle())
        .update(device_->handle());
    return Ok{};
}

}  // namespace lc::client
