#include "editor_client/render/passes/draw_pair_set.h"

#include <array>
#include <vector>

#include "lightcuts/device/bindings.h"
#include "lightcuts/tree/draw_pairs.h"

namespace lc::client {

Result<DrawPairSet> DrawPairSet::create(const vk::Device& device) {
    DrawPairSet set(device);
    static_assert(kBindDrawPairs == 0u);
    const VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    Result<vk::DescriptorSetLayout> layout =
        vk::DescriptorSetLayout::create(device.handle(), std::span(&type, 1), VK_SHADER_STAGE_COMPUTE_BIT);
    if (!layout) return make_error(layout.error());
    set.set_layout_ = std::move(layout).value();
    const std::array<VkDescriptorPoolSize, 1> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
    Result<vk::DescriptorPool> pool = vk::DescriptorPool::create(device.handle(), 1, sizes);
    if (!pool) return make_error(pool.error());
    set.pool_ = std::move(pool).value();
    Result<VkDescriptorSet> allocated = set.pool_.allocate(set.set_layout_);
    if (!allocated) return make_error(allocated.error());
    set.set_ = *allocated;
    return set;
}

Status DrawPairSet::upload(const vk::CommandPool& pool, std::span<const GpuTreeNode> nodes) {
    const std::vector<GpuDrawPair> pairs = make_draw_pairs(nodes);
    Result<vk::Buffer> buffer = vk::Buffer::create_with_data(
        *device_, pool, std::as_bytes(std::span(pairs)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!buffer) return make_error("real-time draw records: " + buffer.error());
    pairs_ = std::move(buffer).value();
    vk::DescriptorWriter(set_).storage_buffer(kBindDrawPairs, pairs_.handle()).update(device_->handle());
    return Ok{};
}

}  // namespace lc::client
