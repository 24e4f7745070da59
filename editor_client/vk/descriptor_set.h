#pragma once
// Descriptor set layouts, a pool that owns the sets it hands out, and a writer
// that points a set's bindings at buffers and images.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "editor_client/vk/device_handle.h"
#include "lightcuts/result.h"

namespace lc::vk {

class DescriptorSetLayout {
public:
    static Result<DescriptorSetLayout> create(
        VkDevice device, std::span<const VkDescriptorSetLayoutBinding> bindings);
    // Bindings 0..n-1, binding b one descriptor of types[b], seen by `stages`.
    static Result<DescriptorSetLayout> create(VkDevice device, std::span<const VkDescriptorType> types,
                                              VkShaderStageFlags stages);

    VkDescriptorSetLayout handle() const { return layout_.get(); }

private:
    DeviceHandle<VkDescriptorSetLayout> layout_;
};

class DescriptorPool {
public:
    // Room for `max_sets` sets with at most `sizes` descriptors in total.
    static Result<DescriptorPool> create(VkDevice device, uint32_t max_sets,
                                         std::span<const VkDescriptorPoolSize> sizes);

    // The set is freed with the pool.
    Result<VkDescriptorSet> allocate(const DescriptorSetLayout& layout) const;

private:
    DeviceHandle<VkDescriptorPool> pool_;
};

// Collects writes for one set, then applies them in one vkUpdateDescriptorSets.
class DescriptorWriter {
public:
    explicit DescriptorWriter(VkDescriptorSet set) : set_(set) {}

    DescriptorWriter& storage_buffer(uint32_t binding, VkBuffer buffer);
    DescriptorWriter& storage_image(uint32_t binding, VkImageView view);
    DescriptorWriter& sampled_image(uint32_t binding, VkImageView view, VkSampler sampler);
    void update(VkDevice device);

private:
    VkDescriptorSet set_;
    // Deques keep the addresses the writes point at stable while we append.
    std::deque<VkDescriptorBufferInfo> buffers_;
    std::deque<VkDescriptorImageInfo> images_;
    std::vector<VkWriteDescriptorSet> writes_;
};

}  // namespace lc::vk
