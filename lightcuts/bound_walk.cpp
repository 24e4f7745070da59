#include "lightcuts/bound_walk.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace lc {
namespace {

double max_channel(const glm::dvec3& v) { return std::max({v.x, v.y, v.z}); }

struct Pass {
    glm::dvec3 radiance{0.0};
    uint32_t size = 0;
    uint32_t hash = 0;
    double worst = 0.0;  // largest bound among the cut's non-leaf nodes
};

// The cut of every node whose bound exceeds tau refined (mixed-type junctions
// always). The cut is a function of tau alone, so the walk's order does not
// matter; the shader walks in pre-order. An explicit stack, no recursion: a
// chain-shaped tree is as deep as it has lights.
Pass walk_pass(const LightTree& tree, const SurfacePoint& p, double tau) {
    Pass pass;
    std::vector<int32_t> stack{0};
    while (!stack.empty()) {
        const int32_t index = stack.back();
        stack.pop_back();
        const LightTreeNode& node = tree.nodes[size_t(index)];
        int32_t children[2];
        const int child_count = valid_children(tree, index, children);
        double key = 0.0;  // a leaf is exact
        bool refine = false;
        if (child_count > 0) {
            if (node.mixed_types) {
                refine = true;
            } else {
                key = max_channel(node_contribution_bound(node, p));
                refine = key > tau;
            }
        }
        if (refine) {
            for (int c = child_count - 1; c >= 0; --c) stack.push_back(children[c]);
            continue;
        }
        pass.radiance += shade_node(node, p);
        pass.size += 1;
        pass.hash += cut_hash_term(uint32_t(index));
        pass.worst = std::max(pass.worst, key);
    }
    return pass;
}

}  // namespace

double bisection_threshold(double fit_hi, double over_lo) {
    return std::sqrt(fit_hi) * std::sqrt(std::max(over_lo, fit_hi * 1e-6));
}

CutResult bound_walk_cut(const LightTree& tree, const SurfacePoint& p, const CutSettings& settings) {
    CutResult result;
    if (tree.empty()) return result;
    const double error_ratio = settings.error_ratio >= 0.0 ? settings.error_ratio : 0.0;
    const uint32_t max_cut = std::max<uint32_t>(settings.max_cut, 1);
    double tau = std::numeric_limits<double>::infinity();
    bool bisecting = false;
    double fit_hi = 0.0;   // largest bound on the last cut that fit: any tau >= it gives that cut
    double over_lo = 0.0;  // a tau whose cut exceeded max_cut
    uint32_t bisections_left = kWalkBisections;
    for (uint32_t pass_index = 0; pass_index < kWalkMaxPasses; ++pass_index) {
        const Pass pass = walk_pass(tree, p, tau);
        result.passes = pass_index + 1;
        // Pass 0 is the per-type roots and always kept, whatever max_cut says.
        if (pass_index > 0 && pass.size > max_cut) {
            bisecting = true;
            over_lo = tau;
        } else {
            result.radiance = pass.radiance;
            result.cut_size = pass.size;
            result.cut_hash = pass.hash;
            const double limit = error_ratio * std::max(max_channel(pass.radiance), 0.0);
            if (!(pass.worst > limit)) return result;  // the rule holds: not a max-cut hit
            fit_hi = pass.worst;
            if (!bisecting) {
                tau = std::max(double(kWalkMargin) * limit, pass.worst / double(kWalkShrink));
                continue;
            }
        }
        if (bisections_left == 0) break;
        --bisections_left;
        tau = bisection_threshold(fit_hi, over_lo);
    }
    result.max_cut_hit = true;  // stopped by max_cut, or still refining after the last pass
    return result;
}

}  // namespace lc
