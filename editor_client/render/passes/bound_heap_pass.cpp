#include "editor_client/render/passes/bound_heap_pass.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <bit>
#include <string>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"

namespace lc::client {

std::vector<uint32_t> heap_capacities(uint32_t max_cut) {
    // Room for one refinement (two children) even at max-cut 1.
    uint32_t capacity = std::max(max_cut, 2u);
    std::vector<uint32_t> tries{capacity};
    while (capacity > kMinHeapCapacity) {
        capacity = std::max(kMinHeapCapacity, uint32_t(uint64_t(capacity) * 3 / 4));
        tries.push_back(capacity);
    }
    return tries;
}

void BoundHeapPass::specialize(vk::Specialization& spec, const Frame& frame) const {
    LightcutsPass::specialize(spec, frame);
    spec.set_uint(kSpecErrorRatio, std::bit_cast<uint32_t>(frame.settings->error_ratio))
        .set_uint(kSpecMaxCut, std::max(frame.settings->max_cut, 2u));
}

Result<VkPipeline> BoundHeapPass::create_pipeline(PipelineCache& pipelines, const Frame& frame) {
    std::string refusal = "no capacity to try";
    for (uint32_t capacity : heap_capacities(frame.settings->max_cut)) {
        if (capacity >= smallest_refused_) continue;
        vk::Specialization spec = specialization(frame);
        spec.set_uint(kSpecHeapCapacity, capacity);
        Result<VkPipeline> pipeline = pipelines.compute(frame.compute_layout, module(frame), spec);
        if (pipeline) {
            if (capacity < frame.settings->max_cut && capacity != capacity_)
                spdlog::warn("the heap search holds {} entries on this device (the driver refused {} "
                             "bytes of private memory for {}): pixels reaching it count as max-cut hits",
                             capacity, 20u * smallest_refused_, smallest_refused_);
            capacity_ = capacity;
            return pipeline;
        }
        smallest_refused_ = capacity;
        refusal = pipeline.error();
    }
    return make_error("the heap search's private memory was refused even at " +
                      std::to_string(kMinHeapCapacity) + " entries (" + refusal +
                      "); use --bound-search walk");
}

}  // namespace lc::client
