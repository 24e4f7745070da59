#include "editor_client/render/passes/reference_pass.h"

#include <algorithm>

#include "editor_client/render/gpu/workgroup_lattice.h"
#include "editor_client/vk/barriers.h"
#include "reference_comp.spv.h"

namespace lc::client {
namespace {

// Workgroups a dispatch needs to keep every thread of the device busy: an
// 8x8 image is one workgroup, which lavapipe runs on one thread.
constexpr uint64_t kBusyWorkgroups = 64;

// Parts each dispatch splits its leaves into (shaders/reference.comp): layers
// of workgroups enough to keep the device busy, as many as the walk search's
// per-pixel scratch holds (RenderTargets sizes it for small images), at most
// one per leaf; 1 on images with workgroups enough.
uint32_t reference_parts(const Frame& frame) {
    const uint64_t size = frame.workgroup_size;
    uint64_t groups = 0;
    for (const PixelRegion& r : frame.regions) groups += ((r.width + size - 1) / size) * ((r.height + size - 1) / size);
    groups = std::max<uint64_t>(groups, 1);
    const uint64_t pixels = uint64_t(frame.targets->width) * frame.targets->height;
    const uint64_t scratch = frame.targets->walk_states.size() / sizeof(GpuWalkState);
    const uint64_t parts = std::min({(kBusyWorkgroups + groups - 1) / groups, scratch / pixels,
                                     uint64_t(frame.constants.leaf_count)});
    return uint32_t(std::max<uint64_t>(parts, 1));
}

void dispatch_layers(VkCommandBuffer cmd, const Frame& frame, GpuFrameConstants constants, uint32_t layers) {
    const uint32_t size = frame.workgroup_size;
    if (std::optional<WorkgroupLattice> lattice = workgroup_lattice(frame.regions, size)) {
        // One dispatch keeps every thread busy (a tile-strided reference).
        constants.lattice_step = lattice->step;
        constants.lattice_origin_x = lattice->origin_x;
        constants.lattice_origin_y = lattice->origin_y;
        vkCmdPushConstants(cmd, frame.compute_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants),
                           &constants);
        vkCmdDispatch(cmd, lattice->count_x, lattice->count_y, layers);
        return;
    }
    vkCmdPushConstants(cmd, frame.compute_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants),
                       &constants);
    for (const PixelRegion& r : frame.regions)
        vkCmdDispatchBase(cmd, r.x / size, r.y / size, 0, (r.width + size - 1) / size,
                          (r.height + size - 1) / size, layers);
}

}  // namespace

std::span<const uint32_t> ReferencePass::module(const Frame&) const {
    return spirv_words(reference_comp_spv);
}

ReferenceWork reference_work(const Frame& frame) {
    const uint32_t parts = reference_parts(frame);
    const uint64_t leaf_count = frame.constants.leaf_count;
    const uint64_t per_dispatch = uint64_t(frame.reference_chunk) * parts;
    uint64_t pixels = 0;
    for (const PixelRegion& r : frame.regions) pixels += r.pixels();
    ReferenceWork work;
    // At least one dispatch, even without leaves (the classic lights and emission),
    // for the sums and for each of the exact clamp's passes.
    const uint32_t per_pass =
        uint32_t(std::max<uint64_t>((leaf_count + per_dispatch - 1) / per_dispatch, 1)) + (parts > 1 ? 1u : 0u);
    work.dispatches = per_pass * (1 + frame.constants.clamp_passes);
    work.evaluations_per_dispatch = pixels * std::min(per_dispatch, std::max<uint64_t>(leaf_count, 1));
    return work;
}

std::vector<DispatchRange> reference_submissions(const Frame& frame,
                                                 uint64_t evaluations_per_submission) {
    const ReferenceWork work = reference_work(frame);
    const uint64_t per_submission = std::max<uint64_t>(
        evaluations_per_submission / std::max<uint64_t>(work.evaluations_per_dispatch, 1), 1);
    std::vector<DispatchRange> runs;
    for (uint64_t begin = 0; begin < work.dispatches; begin += per_submission)
        runs.push_back({uint32_t(begin),
                        uint32_t(std::min<uint64_t>(begin + per_submission, work.dispatches))});
    return runs;
}

void ReferencePass::dispatch_all(VkCommandBuffer cmd, const Frame& frame) const {
    // Each dispatch adds its leaves to the previous dispatches' sums (those of
    // an earlier submission too); each of its parts stays within the loop budget.
    const uint32_t parts = reference_parts(frame);
    const DispatchRange range = frame.reference_dispatches;
    GpuFrameConstants constants = frame.constants;
    const uint32_t leaf_count = constants.leaf_count;
    const uint64_t per_dispatch = uint64_t(frame.reference_chunk) * parts;
    uint32_t index = 0;
    // The sums (pass 0), then the exact clamp's passes over the same leaves.
    for (uint32_t pass = 0; pass <= frame.constants.clamp_passes; ++pass) {
        constants.clamp_pass = pass;
        uint32_t begin = 0;
        do {
            constants.light_begin = begin;
            constants.light_end = uint32_t(std::min<uint64_t>(leaf_count, begin + per_dispatch));
            if (range.contains(index)) {
                if (begin > 0 || pass > 0)
                    vk::memory_barrier(cmd, kComputeStage, kStorageReadWrite, kComputeStage,
                                       kStorageReadWrite);
                dispatch_layers(cmd, frame, constants, parts);
            }
            begin = constants.light_end;
            ++index;
        } while (begin < leaf_count);
        if (parts > 1) {
            if (range.contains(index)) {
                // The parts' sums, added in order.
                vk::memory_barrier(cmd, kComputeStage, kStorageReadWrite, kComputeStage,
                                   kStorageReadWrite);
                constants.light_begin = constants.light_end = leaf_count;
                dispatch_layers(cmd, frame, constants, parts);
            }
            ++index;
        }
    }
}

}  // namespace lc::client
