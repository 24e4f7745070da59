#include "editor_client/vk/sampler.h"

#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<Sampler> Sampler::create_linear_repeat(VkDevice device) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = VK_FILTER_LINEAR;
    info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.addressModeV = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.maxLod = 0.0f;
    VkSampler handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateSampler(device, &info, nullptr, &handle));
    Sampler sampler;
    sampler.sampler_ = DeviceHandle<VkSampler>(device, handle, vkDestroySampler);
    return sampler;
}

}  // namespace lc::vk
