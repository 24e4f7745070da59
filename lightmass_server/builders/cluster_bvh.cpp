#include "lightmass_server/builders/cluster_bvh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace lc::bake {
namespace {

constexpr uint32_t kLeafSlots = 4;
static_assert(kLeafSlots < 8, "ClusterBvh::Node::count holds 3 bits");

OrientationCone as_cone(const glm::dvec3& axis, double spread) {
    return spread >= std::numbers::pi ? OrientationCone{} : OrientationCone{axis, std::cos(spread)};
}

double half_angle(const OrientationCone& cone) {
    return cone.is_full() ? std::numbers::pi : std::acos(std::clamp(cone.cos_theta, -1.0, 1.0));
}

}  // namespace

GroupBounds ClusterBvh::group_bounds(uint32_t node) const {
    const Node& n = nodes_[node];
    GroupBounds g;
    g.lo = n.lo;
    g.hi = n.hi;
    g.min_I = n.min_I;
    if (!cones_.empty()) {
        g.axis = cones_[node].axis;
        g.spread = cones_[node].spread;
        g.min_theta = cones_[node].min_theta;
    }
    return g;
}

void ClusterBvh::refit_leaf(const ClusterSet& set, uint32_t node_index) {
    Node& node = nodes_[node_index];
    node.lo = glm::dvec3(std::numeric_limits<double>::max());
    node.hi = glm::dvec3(std::numeric_limits<double>::lowest());
    node.min_I = std::numeric_limits<double>::max();
    node.live = 0;
    OrientationCone cone;
    double min_theta = std::numbers::pi;
    for (uint32_t s = node.first; s < node.first + node.count; ++s) {
        const Slot& slot = slots_[s];
        if (slot.id == kNoCluster) continue;
        node.lo = glm::min(node.lo, slot.shape.lo);
        node.hi = glm::max(node.hi, slot.shape.hi);
        node.min_I = std::min(node.min_I, slot.shape.I);
        if (set.params.oriented()) {
            const ClusterCone& c = set.cones[slot.id];
            const OrientationCone member{c.axis, c.cos_theta};
            cone = node.live == 0 ? member : cone_union(cone, member);
            min_theta = std::min(min_theta, c.theta);
        }
        ++node.live;
    }
    if (set.params.oriented()) {
        cones_[node_index] = ConeBounds{cone.axis, half_angle(cone), min_theta};
    }
}

void ClusterBvh::refit_inner(const ClusterSet& set, uint32_t node_index) {
    Node& node = nodes_[node_index];
    const Node& l = nodes_[node.first];
    const Node& r = nodes_[node.first + 1];
    node.live = l.live + r.live;
    node.lo = glm::min(l.lo, r.lo);
    node.hi = glm::max(l.hi, r.hi);
    node.min_I = std::min(l.min_I, r.min_I);
    if (set.params.oriented()) {
        const ConeBounds& cl = cones_[node.first];
        const ConeBounds& cr = cones_[node.first + 1];
        const OrientationCone cone =
            cone_union(as_cone(cl.axis, cl.spread), as_cone(cr.axis, cr.spread));
        cones_[node_index] =
            ConeBounds{cone.axis, half_angle(cone), std::min(cl.min_theta, cr.min_theta)};
    }
}

namespace {

// Each id beside its centre: the splits below compare and move them together,
// reading memory in order rather than a centre per id at random.
struct Centred {
    glm::dvec3 centre;
    uint32_t id;
};

std::vector<Centred> centred_ids(const ClusterSet& set, std::span<const uint32_t> ids) {
    std::vector<Centred> order(ids.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, ids.size(), 1u << 14),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t i = r.begin(); i != r.end(); ++i) {
                              const ClusterShape& shape = set.shapes[ids[i]];
                              order[i] = Centred{0.5 * (shape.lo + shape.hi), ids[i]};
                          }
                      });
    return order;
}

// A range of `order`, split at `mid` into the ranges at first_child and
// first_child + 1 (breadth-first in their list).
struct SplitRange {
    uint32_t begin, end;
    uint32_t mid = 0;          // 0: a leaf range
    uint32_t first_child = 0;  // index in the list of ranges
};

// The median along the range's longest axis of centres, ties by id.
void split_at_median(std::vector<Centred>& order, SplitRange& r) {
    if (r.end - r.begin <= kLeafSlots) return;
    glm::dvec3 lo(std::numeric_limits<double>::max());
    glm::dvec3 hi(std::numeric_limits<double>::lowest());
    for (uint32_t s = r.begin; s < r.end; ++s) {
        lo = glm::min(lo, order[s].centre);
        hi = glm::max(hi, order[s].centre);
    }
    const glm::dvec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    r.mid = r.begin + (r.end - r.begin) / 2;
    std::nth_element(order.begin() + r.begin, order.begin() + r.mid, order.begin() + r.end,
                     [&](const Centred& a, const Centred& b) {
                         const double ca = a.centre[axis];
                         const double cb = b.centre[axis];
                         return ca < cb || (ca == cb && a.id < b.id);
                     });
}

// The median splits, one depth at a time: the ranges of one depth are
// disjoint, so they are split in parallel, each exactly as it would be alone.
std::vector<SplitRange> median_split_ranges(std::vector<Centred>& order) {
    std::vector<SplitRange> ranges{{0, uint32_t(order.size())}};
    for (size_t depth_begin = 0; depth_begin < ranges.size();) {
        const size_t depth_end = ranges.size();
        tbb::parallel_for(tbb::blocked_range<size_t>(depth_begin, depth_end, 1),
                          [&](const tbb::blocked_range<size_t>& chunk) {
                              for (size_t k = chunk.begin(); k != chunk.end(); ++k)
                                  split_at_median(order, ranges[k]);
                          });
        for (size_t k = depth_begin; k < depth_end; ++k) {
            if (ranges[k].mid == 0) continue;
            ranges[k].first_child = uint32_t(ranges.size());
            const SplitRange r = ranges[k];
            ranges.push_back(SplitRange{r.begin, r.mid});
            ranges.push_back(SplitRange{r.mid, r.end});
        }
        depth_begin = depth_end;
    }
    return ranges;
}

}  // namespace

void ClusterBvh::build(const ClusterSet& set, std::span<const uint32_t> ids, size_t id_capacity) {
    nodes_.clear();
    parent_.clear();
    cones_.clear();
    live_total_ = 0;
    slots_.resize(ids.size());
    slot_of_.assign(id_capacity, kNoCluster);
    leaf_of_slot_.assign(ids.size(), 0);
    if (ids.empty()) return;

    std::vector<Centred> order = centred_ids(set, ids);
    const std::vector<SplitRange> ranges = median_split_ranges(order);

    // The nodes, numbered depth-first (a subtree's nodes close together,
    // which the searches' caches like): a work list, no recursion.
    nodes_.reserve(2 * (ids.size() / kLeafSlots + 1));
    parent_.reserve(nodes_.capacity());
    nodes_.push_back(Node{});
    parent_.push_back(-1);
    struct Pending {
        uint32_t node, range;
    };
    std::vector<Pending> pending{{0, 0}};
    while (!pending.empty()) {
        const Pending p = pending.back();
        pending.pop_back();
        const SplitRange& r = ranges[p.range];
        if (r.mid == 0) {
            nodes_[p.node].first = r.begin;
            nodes_[p.node].count = r.end - r.begin;
            for (uint32_t s = r.begin; s < r.end; ++s) leaf_of_slot_[s] = p.node;
            continue;
        }
        const uint32_t left = uint32_t(nodes_.size());
        nodes_.push_back(Node{});
        nodes_.push_back(Node{});
        parent_.push_back(int32_t(p.node));
        parent_.push_back(int32_t(p.node));
        nodes_[p.node].first = left;
        pending.push_back({left, r.first_child});
        pending.push_back({left + 1, r.first_child + 1});
    }
    for (uint32_t s = 0; s < order.size(); ++s) {
        slots_[s] = Slot{set.shapes[order[s].id], order[s].id};
        slot_of_[order[s].id] = s;
    }
    if (set.params.oriented()) cones_.resize(nodes_.size());
    refit(set);
}

void ClusterBvh::refit(const ClusterSet& set) {
    // Children always come after their parent: bottom-up in reverse order.
    for (size_t i = nodes_.size(); i-- > 0;) {
        if (nodes_[i].is_leaf()) {
            refit_leaf(set, uint32_t(i));
        } else {
            refit_inner(set, uint32_t(i));
        }
    }
    live_total_ = nodes_.empty() ? 0 : nodes_[0].live;
}

void ClusterBvh::scan_leaf(const ClusterSet& set, uint32_t a, uint32_t node_index,
                           NearestCluster& best) const {
    const Node& node = nodes_[node_index];
    const ClusterShape& shape_a = set.shapes[a];
    static const ClusterCone kUnusedCone;
    const ClusterCone& cone_a = set.params.oriented() ? set.cones[a] : kUnusedCone;
    for (uint32_t s = node.first; s < node.first + node.count; ++s) {
        const Slot& slot = slots_[s];
        if (slot.id == kNoCluster || slot.id == a) continue;
        const ClusterCone& cone_b = set.params.oriented() ? set.cones[slot.id] : kUnusedCone;
        const double metric = cluster_metric(set.params, shape_a, slot.shape, cone_a, cone_b);
        if (metric < best.metric) best = NearestCluster{metric, slot.id};
    }
}

NearestCluster ClusterBvh::nearest(const ClusterSet& set, uint32_t a, uint32_t hint,
                                   std::vector<std::pair<double, uint32_t>>& stack) const {
    NearestCluster best;
    if (hint != kNoCluster) best = NearestCluster{cluster_metric(set, a, hint), hint};
    const ClusterShape& A = set.shapes[a];
    const auto bound = [&](uint32_t node) {
        if (set.params.oriented()) return cluster_metric_lower_bound(set, a, group_bounds(node));
        // cluster_metric_lower_bound without orientation, on the node in place.
        const Node& n = nodes_[node];
        const glm::dvec3 extent = glm::max(A.hi - A.lo, glm::max(n.lo - A.lo, A.hi - n.hi));
        // Same association as cluster_metric, so rounding keeps bound <= metric.
        return (A.I + n.min_I + set.params.intensity_floor) * glm::dot(extent, extent);
    };
    // Ties go to the cluster found first in this (deterministic) search order,
    // nearest in the hierarchy: a subtree that cannot do strictly better is
    // skipped, so coincident clusters do not make every search visit them all.

    // a's own leaf first, then each ancestor's other child: the closest
    // clusters are usually found first, and they prune the rest.
    uint32_t child = leaf_of_slot_[slot_of_[a]];
    scan_leaf(set, a, child, best);
    for (int32_t up = parent_[child]; up >= 0; child = uint32_t(up), up = parent_[child]) {
        const Node& parent = nodes_[size_t(up)];
        const uint32_t sibling = parent.first == child ? parent.first + 1 : parent.first;
        if (nodes_[sibling].live == 0) continue;
        stack.clear();
        stack.emplace_back(bound(sibling), sibling);
        while (!stack.empty()) {
            const auto [node_bound, node_index] = stack.back();
            stack.pop_back();
            // Checked when popped: best may have improved since the push.
            if (!(node_bound < best.metric)) continue;
            const Node& node = nodes_[node_index];
            if (node.is_leaf()) {
                scan_leaf(set, a, node_index, best);
                continue;
            }
            const uint32_t l = node.first;
            const uint32_t r = node.first + 1;
            const bool l_live = nodes_[l].live > 0;
            const bool r_live = nodes_[r].live > 0;
            const double bl = l_live ? bound(l) : 0.0;
            const double br = r_live ? bound(r) : 0.0;
            // Nearer child last, so it is searched first.
            if (l_live && r_live) {
                if (bl <= br) {
                    stack.emplace_back(br, r);
                    stack.emplace_back(bl, l);
                } else {
                    stack.emplace_back(bl, l);
                    stack.emplace_back(br, r);
                }
            } else if (l_live) {
                stack.emplace_back(bl, l);
            } else if (r_live) {
                stack.emplace_back(br, r);
            }
        }
    }
    return best;
}

void ClusterBvh::grow_to_include(const ClusterSet& set, uint32_t node_index, uint32_t cluster) {
    const ClusterShape& shape = set.shapes[cluster];
    for (int32_t i = int32_t(node_index); i >= 0; i = parent_[size_t(i)]) {
        Node& node = nodes_[size_t(i)];
        bool changed = false;
        const glm::dvec3 lo = glm::min(node.lo, shape.lo);
        const glm::dvec3 hi = glm::max(node.hi, shape.hi);
        if (lo != node.lo || hi != node.hi) {
            node.lo = lo;
            node.hi = hi;
            changed = true;
        }
        if (set.params.oriented()) {
            ConeBounds& bounds = cones_[size_t(i)];
            const ClusterCone& c = set.cones[cluster];
            const OrientationCone grown =
                cone_union(as_cone(bounds.axis, bounds.spread), {c.axis, c.cos_theta});
            const double spread = half_angle(grown);
            if (spread > bounds.spread) {
                bounds.axis = grown.axis;
                bounds.spread = spread;
                changed = true;
            }
        }
        // Ancestors hold this node's bounds: nothing above can change either.
        if (!changed) return;
    }
}

void ClusterBvh::merge(const ClusterSet& set, uint32_t kept, uint32_t removed, uint32_t merged) {
    // min_I and min_theta stay valid lower bounds: a merged cluster is brighter
    // and its cone wider than the child whose slot it takes.
    const uint32_t kept_slot = slot_of_[kept];
    slots_[kept_slot] = Slot{set.shapes[merged], merged};
    slot_of_[merged] = kept_slot;
    slot_of_[kept] = kNoCluster;
    grow_to_include(set, leaf_of_slot_[kept_slot], merged);

    const uint32_t removed_slot = slot_of_[removed];
    slots_[removed_slot].id = kNoCluster;
    slot_of_[removed] = kNoCluster;
    // Only the leaf's count: an inner node's waits for the next refit (see Node::live).
    --nodes_[leaf_of_slot_[removed_slot]].live;
    --live_total_;
}

}  // namespace lc::bake
