#include "editor_client/vk/specialization.h"

#include <algorithm>

namespace lc::vk {

Specialization& Specialization::set_uint(uint32_t id, uint32_t value) {
    for (size_t i = 0; i < entries_.size(); ++i) {
        if (entries_[i].constantID == id) {
            values_[i] = value;
            return *this;
        }
    }
    entries_.push_back(
        {id, static_cast<uint32_t>(values_.size() * sizeof(uint32_t)), sizeof(uint32_t)});
    values_.push_back(value);
    return *this;
}

std::vector<std::pair<uint32_t, uint32_t>> Specialization::constants() const {
    std::vector<std::pair<uint32_t, uint32_t>> out;
    out.reserve(entries_.size());
    for (size_t i = 0; i < entries_.size(); ++i) out.emplace_back(entries_[i].constantID, values_[i]);
    std::sort(out.begin(), out.end());
    return out;
}

const VkSpecializationInfo* Specialization::info() {
    info_.mapEntryCount = static_cast<uint32_t>(entries_.size());
    info_.pMapEntries = entries_.data();
    info_.dataSize = values_.size() * sizeof(uint32_t);
    info_.pData = values_.data();
    return &info_;
}

}  // namespace lc::vk
