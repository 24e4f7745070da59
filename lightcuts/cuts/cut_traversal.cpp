#include "lightcuts/cuts/cut_traversal.h"

#include <limits>

namespace lc {

double max_channel(const glm::dvec3& v) { return std::max({v.x, v.y, v.z}); }

void CutTally::add(int32_t node_index, const GpuTreeNode& node, const glm::dvec3& node_radiance) {
    radiance += node_radiance;
    // The paper clamps single lights; clusters are the refinement's.
    device::add_cut_node(indirect, is_indirect(node),
                         device::clamped_leaf(is_indirect(node), is_patch(node), is_leaf(node)),
                         node_radiance);
    size += 1;
    hash += cut_hash_term(uint32_t(node_index));
}

void CutTally::copy_to(CutResult& result, double clamp_ratio) const {
    result.radiance = radiance;
    result.cut_size = size;
    result.cut_hash = hash;
    result.indirect = indirect.largest + indirect.second + indirect.rest + indirect.clusters;
    result.clamped = glm::dvec3(0.0);
    if (indirect.leaves > 0) result.radiance = device::indirect_clamped(radiance, indirect, clamp_ratio, result.clamped);
}

double error_key(const WalkTree& tree, int32_t index, const SurfacePoint& p) {
    const GpuTreeNode& node = tree.node(index);
    if (is_leaf(node)) return 0.0;
    if (joins_types(node)) return std::numeric_limits<double>::infinity();
    return max_channel(node_contribution_bound(tree, index, p));
}

double indirect_clamp_ratio(double error_ratio) { return 0.5 * std::max(error_ratio, 0.0); }

BoundRule::BoundRule(const CutSettings& settings)
    : error_ratio(settings.error_ratio >= 0.0 ? settings.error_ratio : 0.0),
      max_cut(std::max<uint32_t>(settings.max_cut, 1)) {}

double BoundRule::limit(const glm::dvec3& total) const {
    return error_ratio * std::max(max_channel(total), 0.0);
}

}  // namespace lc
