// The debug messenger really counts validation messages, so the "zero
// messages" assertions of the other renderer tests can fail.
#include <gtest/gtest.h>

#include "editor_client/vk/context.h"
#include "render_test_support.h"

namespace lc::vk {
namespace {

TEST(Validation, MisuseIsCountedAndReported) {
    std::unique_ptr<Context> context;
    LC_REQUIRE_VULKAN(context);
    if (!context->validation_enabled())
        GTEST_SKIP() << "the Khronos validation layer is not installed";
    EXPECT_EQ(context->validation_message_count(), 0u);

    // Anisotropic filtering without enabling the samplerAnisotropy feature is
    // invalid usage (VUID-VkSamplerCreateInfo-anisotropyEnable-01070).
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.anisotropyEnable = VK_TRUE;
    info.maxAnisotropy = 4.0f;
    VkSampler sampler = VK_NULL_HANDLE;
    VkResult result = vkCreateSampler(context->device().handle(), &info, nullptr, &sampler);
    if (result == VK_SUCCESS) vkDestroySampler(context->device().handle(), sampler, nullptr);
    EXPECT_GE(context->validation_message_count(), 1u);
}

}  // namespace
}  // namespace lc::vk
