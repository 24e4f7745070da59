#pragma once
// Specialization constants (workgroup size, effects switched on or off) packed
// for VkSpecializationInfo. Every constant is 32 bits wide (bool as VkBool32).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace lc::vk {

class Specialization {
public:
    Specialization& set_uint(uint32_t id, uint32_t value);
    Specialization& set_bool(uint32_t id, bool value) { return set_uint(id, value ? 1u : 0u); }

    // (id, value) pairs ordered by id: equal for equal specializations.
    std::vector<std::pair<uint32_t, uint32_t>> constants() const;

    // Valid while this object lives and is not modified.
    const VkSpecializationInfo* info();

private:
    std::vector<VkSpecializationMapEntry> entries_;
    std::vector<uint32_t> values_;
    VkSpecializationInfo info_{};
};

}  // namespace lc::vk
