#pragma once
// The one place where the double-precision build becomes the float
// lc::LightTree: breadth-first order from the root (every child index greater
// than its parent's), leaf representatives remapped, and conservative rounding
// so float bounds still hold what the double bounds held: bbox min rounded
// down and max up, radius up, cone cosine down; sums that overflow float clamp
// to the largest float, radii that do become unbounded.
#include <cstdint>

#include "lightcuts/build_tree.h"
#include "lightcuts/light_tree.h"

namespace lc {

struct ExportedTree {
    LightTree tree;
    uint32_t depth = 0;  // edges from the root to the deepest leaf
};

// `root` is an arena index, or kNoBuildChild for an empty tree. Iterative.
ExportedTree export_light_tree(const BuildArena& arena, int32_t root);

// Rounding helpers, exposed for tests.
float round_down_to_float(double value);
float round_up_to_float(double value);

}  // namespace lc
