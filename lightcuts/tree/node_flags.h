#pragma once
// The C++ face of device/node_flags.h: the flags a build node and a float
// node carry, the same bits the wire records and GpuTreeNode carry.
#include <cstdint>

#include "lightcuts/device/node_flags.h"

namespace lc {

struct NodeFlags {
    uint8_t bits = 0;  // kNodeMixedTypes | kNodeIndirect | kNodePatch

    bool mixed_types() const { return (bits & kNodeMixedTypes) != 0; }
    bool indirect() const { return (bits & kNodeIndirect) != 0; }
    bool patch() const { return (bits & kNodePatch) != 0; }
    void set(uint32_t flag, bool on) { bits = uint8_t(on ? (bits | flag) : (bits & ~flag)); }
    bool operator==(const NodeFlags&) const = default;
};

}  // namespace lc
