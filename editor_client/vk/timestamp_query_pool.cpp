#include "editor_client/vk/timestamp_query_pool.h"

#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<TimestampQueryPool> TimestampQueryPool::create(const Device& device, uint32_t count) {
    TimestampQueryPool result;
    result.count_ = count;
    const PhysicalDevice& physical = device.physical();
    result.supported_ = physical.timestamp_valid_bits > 0 && count > 0;
    result.period_ns_ = physical.properties.limits.timestampPeriod;
    result.valid_mask_ = physical.timestamp_valid_bits >= 64
                             ? ~0ull
                             : (1ull << physical.timestamp_valid_bits) - 1ull;
    if (!result.supported_) return result;
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = count;
    VkQueryPool handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateQueryPool(device.handle(), &info, nullptr, &handle));
    result.pool_ = DeviceHandle<VkQueryPool>(device.handle(), handle, vkDestroyQueryPool);
    return result;
}

void TimestampQueryPool::reset(VkCommandBuffer cmd) const {
    if (supported_) vkCmdResetQueryPool(cmd, pool_.get(), 0, count_);
}

void TimestampQueryPool::write(VkCommandBuffer cmd, VkPipelineStageFlags2 stage,
                               uint32_t index) const {
    if (supported_) vkCmdWriteTimestamp2(cmd, stage, pool_.get(), index);
}

Result<std::vector<double>> TimestampQueryPool::read_ms() const {
    std::vector<double> ms(count_, 0.0);
    if (!supported_) return ms;
    std::vector<uint64_t> ticks(count_);
    LC_VK_CHECK(vkGetQueryPoolResults(
        pool_.device(), pool_.get(), 0, count_, ticks.size() * sizeof(uint64_t), ticks.data(),
        sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    uint64_t start = ticks[0] & valid_mask_;
    for (uint32_t i = 0; i < count_; ++i) {
        // Wrap-around safe difference inside the valid bits.
        uint64_t delta = ((ticks[i] & valid_mask_) - start) & valid_mask_;
        ms[i] = double(delta) * period_ns_ * 1e-6;
    }
    return ms;
}

}  // namespace lc::vk
