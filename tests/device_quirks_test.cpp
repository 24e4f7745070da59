// Device quirks are chosen by driver id: llvmpipe's loop limit, nothing elsewhere.
#include <gtest/gtest.h>

#include "editor_client/vk/device_quirks.h"

namespace lc::vk {
namespace {

TEST(DeviceQuirks, LlvmpipeHasTheLoopLimitOthersNone) {
    EXPECT_EQ(quirks_for_driver(VK_DRIVER_ID_MESA_LLVMPIPE).loop_iteration_limit, 65535u);
    EXPECT_TRUE(quirks_for_driver(VK_DRIVER_ID_MESA_LLVMPIPE).has_loop_limit());
    EXPECT_FALSE(quirks_for_driver(VK_DRIVER_ID_NVIDIA_PROPRIETARY).has_loop_limit());
    EXPECT_FALSE(quirks_for_driver(VK_DRIVER_ID_MESA_RADV).has_loop_limit());
}

}  // namespace
}  // namespace lc::vk
