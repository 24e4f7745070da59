#include "editor_client/render/passes/bound_walk_pass.h"

#include <bit>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"
#include "editor_client/vk/barriers.h"
#include "lightcuts/cuts/bound_walk.h"

namespace lc::client {

void BoundWalkPass::specialize(vk::Specialization& spec, const Frame& frame) const {
    LightcutsPass::specialize(spec, frame);
    // The walk keeps no heap: its array stays at the shader's minimum of 2.
    spec.set_uint(kSpecErrorRatio, std::bit_cast<uint32_t>(frame.settings->error_ratio))
        .set_uint(kSpecWalkMaxCut, frame.settings->max_cut)
        .set_uint(kSpecWalkMaxPasses, kWalkMaxPasses)
        .set_uint(kSpecWalkShrink, std::bit_cast<uint32_t>(kWalkShrink))
        .set_uint(kSpecWalkMargin, std::bit_cast<uint32_t>(kWalkMargin))
        .set_uint(kSpecWalkBisections, kWalkBisections)
        .set_bool(kSpecWalkShareCuts, frame.settings->share_cuts);
}

void BoundWalkPass::dispatch_all(VkCommandBuffer cmd, const Frame& frame) const {
    // A pass that a loop limit cuts short runs again in the next dispatch
    // (the search kept in walk_states); every dispatch completes a pass or
    // ends the search, so kWalkMaxPasses of them end every search. Pixels
    // that are done return at once.
    GpuFrameConstants constants = frame.constants;
    for (uint32_t d = 0; d < kWalkMaxPasses; ++d) {
        constants.walk_dispatch = d;
        if (d > 0)
            vk::memory_barrier(cmd, kComputeStage, kStorageReadWrite, kComputeStage,
                               kStorageReadWrite);
        dispatch(cmd, frame, constants);
    }
}

}  // namespace lc::client
