#include "editor_client/render/passes/reference_pass.h"

#include "editor_client/vk/barriers.h"
#include "reference_comp.spv.h"

namespace lc::client {

std::span<const uint32_t> ReferencePass::module(const Frame&) const {
    return spirv_words(reference_comp_spv);
}

void ReferencePass::dispatch_all(VkCommandBuffer cmd, const Frame& frame) const {
    // Each dispatch adds its leaves to the previous dispatches' sums.
    GpuFrameConstants constants = frame.constants;
    const uint32_t leaf_count = constants.leaf_count;
    const uint32_t chunk = frame.reference_chunk;
    uint32_t begin = 0;
    do {
        constants.light_begin = begin;
        constants.light_end = leaf_count - begin > chunk ? begin + chunk : leaf_count;
        if (begin > 0)
            vk::memory_barrier(cmd, kComputeStage, kStorageReadWrite, kComputeStage,
                               kStorageReadWrite);
        dispatch(cmd, frame, constants);
        begin = constants.light_end;
    } while (begin < leaf_count);
}

}  // namespace lc::client
