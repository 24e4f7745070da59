#include "editor_client/vk/descriptor_set.h"

#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<DescriptorSetLayout> DescriptorSetLayout::create(
    VkDevice device, std::span<const VkDescriptorSetLayoutBinding> bindings) {
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = static_cast<uint32_t>(bindings.size());
    info.pBindings = bindings.data();
    VkDescriptorSetLayout handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateDescriptorSetLayout(device, &info, nullptr, &handle));
    DescriptorSetLayout layout;
    layout.layout_ =
        DeviceHandle<VkDescriptorSetLayout>(device, handle, vkDestroyDescriptorSetLayout);
    return layout;
}

Result<DescriptorSetLayout> DescriptorSetLayout::create(VkDevice device,
                                                       std::span<const VkDescriptorType> types,
                                                       VkShaderStageFlags stages) {
    std::vector<VkDescriptorSetLayoutBinding> bindings(types.size());
    for (size_t b = 0; b < types.size(); ++b) {
        bindings[b].binding = uint32_t(b);
        bindings[b].descriptorType = types[b];
        bindings[b].descriptorCount = 1;
        bindings[b].stageFlags = stages;
    }
    return create(device, bindings);
}

Result<DescriptorPool> DescriptorPool::create(VkDevice device, uint32_t max_sets,
                                              std::span<const VkDescriptorPoolSize> sizes) {
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = max_sets;
    info.poolSizeCount = static_cast<uint32_t>(sizes.size());
    info.pPoolSizes = sizes.data();
    VkDescriptorPool handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateDescriptorPool(device, &info, nullptr, &handle));
    DescriptorPool pool;
    pool.pool_ = DeviceHandle<VkDescriptorPool>(device, handle, vkDestroyDescriptorPool);
    return pool;
}

Result<VkDescriptorSet> DescriptorPool::allocate(const DescriptorSetLayout& layout) const {
    VkDescriptorSetLayout layout_handle = layout.handle();
    VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    info.descriptorPool = pool_.get();
    info.descriptorSetCount = 1;
    info.pSetLayouts = &layout_handle;
    VkDescriptorSet set = VK_NULL_HANDLE;
    LC_VK_CHECK(vkAllocateDescriptorSets(pool_.device(), &info, &set));
    return set;
}

DescriptorWriter& DescriptorWriter::storage_buffer(uint32_t binding, VkBuffer buffer) {
    buffers_.push_back({buffer, 0, VK_WHOLE_SIZE});
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &buffers_.back();
    writes_.push_back(write);
    return *this;
}

DescriptorWriter& DescriptorWriter::storage_image(uint32_t binding, VkImageView view) {
    images_.push_back({VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL});
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    write.pImageInfo = &images_.back();
    writes_.push_back(write);
    return *this;
}

DescriptorWriter& DescriptorWriter::sampled_image(uint32_t binding, VkImageView view,
                                                  VkSampler sampler) {
    images_.push_back({sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    write.pImageInfo = &images_.back();
    writes_.push_back(write);
    return *this;
}

void DescriptorWriter::update(VkDevice device) {
    vkUpdateDescriptorSets(device, static_cast<uint32_t>(writes_.size()), writes_.data(), 0,
                           nullptr);
    writes_.clear();
    buffers_.clear();
    images_.clear();
}

}  // namespace lc::vk
