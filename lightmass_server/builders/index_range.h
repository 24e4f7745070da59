#pragma once
// A half-open range of work items by index: the share of a sampler's items
// (area-light samples, VPL paths) one process makes. Items draw from
// counter-based streams (seed, index), so the shares' outputs, concatenated
// in range order, are the whole run's bytes.
#include <algorithm>
#include <cstdint>
#include <limits>

namespace lc::bake {

struct IndexRange {
    uint64_t begin = 0;
    uint64_t end = std::numeric_limits<uint64_t>::max();  // the default: every item
    bool contains(uint64_t i) const { return i >= begin && i < end; }
};

// The part of [0, count) that share `part` of `parts` equal shares holds
// (the first count % parts shares one item larger).
inline IndexRange share_of(uint64_t count, uint32_t part, uint32_t parts) {
    const uint64_t base = count / parts, extra = count % parts;
    const uint64_t begin = part * base + std::min<uint64_t>(part, extra);
    return {begin, begin + base + (part < extra ? 1 : 0)};
}

}  // namespace lc::bake
