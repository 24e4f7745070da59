#pragma once
// The render's census line for bounced light (issue 16), after "indirect: ":
// what the tree's indirect lights are (VPLs or radiosity patches, told apart
// by their flags), how many bounces they hold and how much the clamp took,
// or why there is none.
#include <cstdint>
#include <optional>
#include <string>

#include "lightcuts/tree/light_tree.h"
#include "protocol/messages.h"

namespace lc::client {

struct IndirectCensusFacts {
    bool has_tree = false;
    uint64_t vpls = 0;      // indirect leaves that are not patches
    uint64_t patches = 0;   // radiosity patches
    bool left_out = false;  // render --indirect off
    double clamped_fraction = 0.0;
    // The deepest bounce among the tree's VPLs (LightTreeNode::bounce); 0: not
    // recorded (a tree from a server before the field was written).
    uint32_t deepest_vpl_bounce = 0;
    // The bake's request when this render baked the tree itself; a tree from
    // a dump holds the result channel only, and says what its VPLs record.
    std::optional<IndirectRequest> baked;
    bool scene_has_geometry = false;  // triangles the server could bounce light on
};

// The largest LightTreeNode::bounce over the tree's VPL leaves.
uint32_t deepest_vpl_bounce(const LightTree& tree);

// Empty when there is no tree to say anything about.
std::string indirect_census(const IndirectCensusFacts& facts);

}  // namespace lc::client
