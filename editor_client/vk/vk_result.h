#pragma once
// Vulkan result codes as lc::Error messages that name the failed call.
#include <vulkan/vulkan.h>

#include <string>

#include "lightcuts/result.h"
#include "lightcuts/status_macros.h"

namespace lc::vk {

const char* result_name(VkResult result);

inline Error call_failed(VkResult result, const char* call) {
    return make_error(std::string(call) + " failed: " + result_name(result));
}

}  // namespace lc::vk

// Returns an lc::Error from the enclosing function when a Vulkan call fails.
#define LC_VK_CHECK(call)                                                                    \
    do {                                                                                     \
        VkResult lc_vk_result_ = (call);                                                     \
        if (lc_vk_result_ != VK_SUCCESS) return ::lc::vk::call_failed(lc_vk_result_, #call); \
    } while (0)
