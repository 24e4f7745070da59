#include "editor_client/vk/shader_module.h"

#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<ShaderModule> ShaderModule::create(VkDevice device, std::span<const uint32_t> spirv) {
    if (spirv.empty()) return make_error("empty SPIR-V module");
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size_bytes();
    info.pCode = spirv.data();
    VkShaderModule handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &handle));
    ShaderModule module;
    module.module_ = DeviceHandle<VkShaderModule>(device, handle, vkDestroyShaderModule);
    return module;
}

}  // namespace lc::vk
