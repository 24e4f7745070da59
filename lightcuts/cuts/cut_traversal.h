#pragma once
// What the CPU's cut searches share (the radius walk and the heap search in
// cpu_evaluator.cpp, the threshold passes in bound_walk.cpp): a node's
// children and error bound, the walk over a cut in pre-order, the tally of a
// cut, and the bound criterion's stopping rule.
#include <glm/vec3.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/device/indirect_clamp.glsl.h"

namespace lc {

double max_channel(const glm::dvec3& v);

// A cut's radiance (cut nodes evaluated as clusters), size and hash, and its
// indirect light for the clamp.
struct CutTally {
    glm::dvec3 radiance{0.0};
    uint32_t size = 0;
    uint32_t hash = 0;
    device::IndirectSums indirect = device::no_indirect_sums();

    void add(int32_t node_index, const GpuTreeNode& node, const glm::dvec3& node_radiance);
    // The cut's part of a CutResult (max_cut_hit and passes left as they are),
    // its indirect leaves clamped at `clamp_ratio` of the cut's total.
    void copy_to(CutResult& result, double clamp_ratio) const;
};

// Whether a search leaves a node (or a leaf light) out of the cut altogether
// (render --indirect off).
inline bool left_out(const GpuTreeNode& node, const CutSettings& settings) {
    return !settings.indirect && is_indirect(node);
}
inline bool left_out(const GpuLight& light, const CutSettings& settings) {
    return !settings.indirect && is_indirect(light);
}

// The bound criterion's key of node `index`: the largest channel of its
// error bound; 0 for a leaf (exact), +inf for a mixed-type junction (always
// refined).
double error_key(const WalkTree& tree, int32_t index, const SurfacePoint& p);

// The bound criterion's rule, from the settings: a cut is done when every
// node's key is <= limit(total), or when it reaches max_cut nodes.
struct BoundRule {
    explicit BoundRule(const CutSettings& settings);
    // error_ratio x the largest channel of the cut's total estimate.
    double limit(const glm::dvec3& total) const;

    double error_ratio;
    uint32_t max_cut;  // at least 1
};

// The cut that `refine(index, node, child_count)` selects, in pre-order: a
// node is refined into its children or taken as a cluster (shaded at p
// and tallied); a node left_out() is neither. An explicit stack, no recursion:
// a chain-shaped tree is as deep as it has lights.
template <typename Refine>
CutTally walk_cut(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings, Refine&& refine) {
    CutTally tally;
    std::vector<int32_t> stack{0};
    while (!stack.empty()) {
        const int32_t index = stack.back();
        stack.pop_back();
        const GpuTreeNode& node = tree.node(index);
        if (left_out(node, settings)) continue;
        int32_t children[2];
        const int child_count = children_of(tree, index, children);
        if (refine(index, node, child_count)) {
            for (int c = child_count - 1; c >= 0; --c) stack.push_back(children[c]);
        } else {
            tally.add(index, node, shade_cluster(tree, index, p, settings));
        }
    }
    return tally;
}

}  // namespace lc
