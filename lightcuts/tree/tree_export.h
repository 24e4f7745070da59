#pragma once
// The one place where the double-precision build becomes the float
// lc::LightTree: breadth-first order from the root (every child index greater
// than its parent's), leaf representatives remapped, and conservative rounding
// so float bounds still hold what the double bounds held: bbox min rounded
// down and max up, radius up, cone cosine down; sums that overflow float clamp
// to the largest float, radii that do become unbounded.
#include <cstddef>
#include <cstdint>
#include <functional>

#include "lightcuts/tree/build_tree.h"
#include "lightcuts/tree/light_tree.h"

namespace lc {

struct ExportedTree {
    LightTree tree;
    uint32_t depth = 0;  // edges from the root to the deepest leaf
};

// Runs body(begin, end) over disjoint ranges covering [0, count), in any order
// and on any threads: how the caller lends its thread pool to the export (this
// library has none). Each output node depends on its index only, so the tree is
// the same however the ranges run.
using ParallelRanges =
    std::function<void(size_t count, const std::function<void(size_t begin, size_t end)>& body)>;

// `root` is an arena index, or kNoChild for an empty tree. Iterative. The
// nodes are converted through `parallel` when given, else on this thread.
ExportedTree export_light_tree(const BuildArena& arena, int32_t root, const ParallelRanges& parallel = {});

// One node as export_light_tree converts it: `first_child` is its left
// child's exported index (the right one follows it), `representative_index`
// the exported index of its representative leaf, whose light is `light`.
// For trees whose nodes are numbered elsewhere (MPI ranks write their own).
LightTreeNode export_node(const BuildNode& node, const SceneLight& light, int32_t first_child,
                          int32_t representative_index);

// Rounding helpers, exposed for tests.
float round_down_to_float(double value);
float round_up_to_float(double value);

}  // namespace lc
