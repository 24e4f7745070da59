#pragma once
// A bounding-volume hierarchy over the live clusters of an agglomerative
// build, answering "which live cluster merges with a into the smallest
// cluster" (ties: the first found, nearest in the hierarchy) by branch and
// bound on cluster_metric_lower_bound. Merges update it in place (the merged
// cluster takes one child's slot, the other slot dies, bounds only grow); the
// builder refits it regularly and rebuilds it once most slots are dead.
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "lightmass_server/builders/cluster_metric.h"

namespace lc::bake {

inline constexpr uint32_t kNoCluster = std::numeric_limits<uint32_t>::max();

struct NearestCluster {
    double metric = std::numeric_limits<double>::infinity();
    uint32_t id = kNoCluster;
};

class ClusterBvh {
public:
    // Builds over the given live cluster ids; `id_capacity` bounds every id
    // that may ever be stored. Iterative; deterministic for equal input.
    void build(const ClusterSet& set, std::span<const uint32_t> ids, size_t id_capacity);

    // The best partner of live cluster `a` among the other live clusters.
    // `hint`: a live cluster other than a (or kNoCluster) whose metric starts
    // the search as its bound. The search starts at a's own leaf and widens
    // through its ancestors' siblings. Thread-safe between updates.
    NearestCluster nearest(const ClusterSet& set, uint32_t a, uint32_t hint,
                           std::vector<std::pair<double, uint32_t>>& stack) const;

    // Recomputes every bound from the live clusters (merges only grow them).
    void refit(const ClusterSet& set);

    // `merged` (already in `set`) takes `kept`'s slot; `removed` leaves.
    void merge(const ClusterSet& set, uint32_t kept, uint32_t removed, uint32_t merged);

    uint32_t slot_of(uint32_t id) const { return slot_of_[id]; }
    size_t slot_count() const { return slots_.size(); }
    size_t live_count() const { return live_total_; }

private:
    // Hot data of the search: one cache line per node (a node's two children
    // are two lines side by side); parents and orientation bounds live apart.
    struct alignas(64) Node {
        glm::dvec3 lo{0.0};
        glm::dvec3 hi{0.0};
        double min_I = 0.0;
        uint32_t first = 0;  // leaf: first slot; inner: left child (right = first + 1)
        uint32_t count : 3 = 0;  // leaf: slot count (at most kLeafSlots); inner: 0
        // Live clusters below: exact in leaves; in inner nodes as of the last
        // refit, so possibly too high since. A search then walks into a
        // subtree that has died and finds nothing there (the same result);
        // merges save a walk to the root each. A build holds at most 2^24 lights.
        uint32_t live : 29 = 0;
        bool is_leaf() const { return count > 0; }
    };
    struct ConeBounds {
        glm::dvec3 axis{0.0, 0.0, -1.0};
        double spread = 0.0;     // half-angle of a cone holding every member cone
        double min_theta = 0.0;  // smallest member half-angle
    };
    // A copy of the cluster's shape next to its id, so scanning a leaf reads
    // one contiguous block.
    struct alignas(64) Slot {
        ClusterShape shape;
        uint32_t id = kNoCluster;  // kNoCluster once dead
    };

    GroupBounds group_bounds(uint32_t node) const;
    void refit_leaf(const ClusterSet& set, uint32_t node);
    void refit_inner(const ClusterSet& set, uint32_t node);
    void grow_to_include(const ClusterSet& set, uint32_t node, uint32_t cluster);
    void scan_leaf(const ClusterSet& set, uint32_t a, uint32_t node, NearestCluster& best) const;

    std::vector<Node> nodes_;
    std::vector<int32_t> parent_;  // -1 at the root
    size_t live_total_ = 0;
    std::vector<ConeBounds> cones_;  // oriented metrics only
    std::vector<Slot> slots_;
    std::vector<uint32_t> slot_of_;       // cluster id -> slot
    std::vector<uint32_t> leaf_of_slot_;  // slot -> leaf node
};

}  // namespace lc::bake
