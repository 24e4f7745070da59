#pragma once
// Shader loop iterations a frame needs per invocation, against a device's
// loop limit (vk::DeviceQuirks::loop_iteration_limit): llvmpipe stops an
// invocation's loops after 65,535 iterations in total, and says nothing
// (shaders/lightcuts/device/limits.h). Reference mode splits its leaves over
// dispatches that each fit (reference_chunk); shadow rays and the bound walk
// notice a walk the limit cut short and count it (loop_limit_stops); other
// work that could exceed the budget is refused with the reason, never
// rendered truncated. Devices without a limit accept everything.
#include <cstdint>

#include "editor_client/render/settings/render_settings.h"
#include "editor_client/vk/device_quirks.h"
#include "lightcuts/result.h"
#include "lightcuts/occlusion/shadow_bvh.h"

namespace lc::client {

// What the loops of one frame run over.
struct LoopWork {
    uint32_t leaf_count = 0;
    uint32_t classic_count = 0;
    uint32_t node_count = 0;
    const ShadowBvh* shadow_bvh = nullptr;  // null or empty: no shadow rays
};

// Leaves per reference dispatch (all of them on devices without a limit).
uint32_t reference_chunk(const vk::DeviceQuirks& quirks, const LoopWork& work);

// Refuses settings whose loops could exceed the device's limit.
Status check_loop_budget(const vk::DeviceQuirks& quirks, const LoopWork& work,
                         const RenderSettings& settings);

}  // namespace lc::client
