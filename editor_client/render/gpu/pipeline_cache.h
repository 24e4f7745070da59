#pragma once
// Compute and graphics pipelines keyed by what makes them differ: the
// pipeline layout, the shader modules and the specialization-constant
// values. A pass asks for the pipeline its settings need; a change of
// settings (a cut criterion, an error ratio, an effect switched on) finds or
// builds another, and going back finds the first again.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "editor_client/vk/compute_pipeline.h"
#include "editor_client/vk/graphics_pipeline.h"
#include "editor_client/vk/specialization.h"
#include "lightcuts/result.h"

namespace lc::client {

class PipelineCache {
public:
    // The least recently used pipeline goes when a new one would exceed
    // `capacity` (an error-ratio slider builds one pipeline per value).
    // Pipelines are only dropped while recording or building, when the
    // previous frame's commands have completed.
    explicit PipelineCache(VkDevice device, size_t capacity = 16);

    Result<VkPipeline> compute(VkPipelineLayout layout, std::span<const uint32_t> spirv,
                               vk::Specialization& specialization);
    // Keyed by the layout, both modules and the fragment specialization: the
    // fixed-function state of a module pair is the same on every call.
    Result<VkPipeline> graphics(const vk::GraphicsPipelineDesc& desc);

    size_t size() const { return entries_.size(); }
    // Whether this compute pipeline is cached (it is not marked as used).
    bool contains(VkPipelineLayout layout, std::span<const uint32_t> spirv,
                  const vk::Specialization& specialization) const;

private:
    struct Key {
        VkPipelineLayout layout = VK_NULL_HANDLE;
        const uint32_t* first_module = nullptr;   // compute, or vertex
        const uint32_t* second_module = nullptr;  // fragment
        std::vector<std::pair<uint32_t, uint32_t>> constants;
        auto operator<=>(const Key&) const = default;
    };
    struct Entry {
        vk::ComputePipeline compute;
        vk::GraphicsPipeline graphics;
        uint64_t last_use = 0;
        VkPipeline handle() const { return compute.handle() ? compute.handle() : graphics.handle(); }
    };
    // The cached pipeline for `key`, marked as used now; null when absent.
    const Entry* find(const Key& key);
    Entry& insert(Key key);

    VkDevice device_;
    size_t capacity_;
    uint64_t clock_ = 0;
    std::map<Key, Entry> entries_;
};

}  // namespace lc::client
