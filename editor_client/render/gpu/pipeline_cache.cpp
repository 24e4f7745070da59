#include "editor_client/render/gpu/pipeline_cache.h"

#include <algorithm>

namespace lc::client {

PipelineCache::PipelineCache(VkDevice device, size_t capacity)
    : device_(device), capacity_(std::max<size_t>(capacity, 1)) {}

const PipelineCache::Entry* PipelineCache::find(const Key& key) {
    auto it = entries_.find(key);
    if (it == entries_.end()) return nullptr;
    it->second.last_use = ++clock_;
    return &it->second;
}

PipelineCache::Entry& PipelineCache::insert(Key key) {
    if (entries_.size() >= capacity_) {
        auto oldest = std::min_element(entries_.begin(), entries_.end(), [](const auto& a, const auto& b) {
            return a.second.last_use < b.second.last_use;
        });
        entries_.erase(oldest);
    }
    Entry& entry = entries_[std::move(key)];
    entry.last_use = ++clock_;
    return entry;
}

bool PipelineCache::contains(VkPipelineLayout layout, std::span<const uint32_t> spirv,
                             const vk::Specialization& specialization) const {
    return entries_.contains(Key{layout, spirv.data(), nullptr, specialization.constants()});
}

Result<VkPipeline> PipelineCache::compute(VkPipelineLayout layout, std::span<const uint32_t> spirv,
                                          vk::Specialization& specialization) {
    Key key{layout, spirv.data(), nullptr, specialization.constants()};
    if (const Entry* cached = find(key)) return cached->handle();
    Result<vk::ComputePipeline> pipeline =
        vk::ComputePipeline::create(device_, layout, spirv, specialization);
    if (!pipeline) return make_error(pipeline.error());
    Entry& entry = insert(std::move(key));
    entry.compute = std::move(pipeline).value();
    return entry.handle();
}

Result<VkPipeline> PipelineCache::graphics(const vk::GraphicsPipelineDesc& desc) {
    Key key{desc.layout, desc.vertex_spirv.data(), desc.fragment_spirv.data(), {}};
    if (desc.fragment_specialization != nullptr)
        key.constants = desc.fragment_specialization->constants();
    if (const Entry* cached = find(key)) return cached->handle();
    Result<vk::GraphicsPipeline> pipeline = vk::GraphicsPipeline::create(device_, desc);
    if (!pipeline) return make_error(pipeline.error());
    Entry& entry = insert(std::move(key));
    entry.graphics = std::move(pipeline).value();
    return entry.handle();
}

}  // namespace lc::client
