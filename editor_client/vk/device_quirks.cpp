#include "editor_client/vk/device_quirks.h"

namespace lc::vk {

DeviceQuirks quirks_for_driver(VkDriverId driver) {
    DeviceQuirks quirks;
    if (driver == VK_DRIVER_ID_MESA_LLVMPIPE) quirks.loop_iteration_limit = 65535;
    return quirks;
}

}  // namespace lc::vk
