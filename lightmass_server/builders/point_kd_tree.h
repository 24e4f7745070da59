#pragma once
// Spatial queries over a fixed 3D point set, answered with a static kd-tree
// (iterative build and traversal). Results are pure functions of the input,
// whatever the thread count: ties in distance go to the smaller point index.
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "lightcuts/tree/build_tree.h"
#include "lightmass_server/control/bake_stop.h"

namespace lc::bake {

struct Neighbor {
    uint32_t index = 0;
    double distance = 0.0;
};

// neighbors[i * k + j]: the j-th nearest other point of point i (nearest
// first). k is clamped to points.size() - 1; `k_used` tells the clamped value.
struct KnnResult {
    uint32_t k_used = 0;
    std::vector<Neighbor> neighbors;

    std::span<const Neighbor> of(uint32_t i) const {
        return std::span<const Neighbor>(neighbors).subspan(size_t(i) * k_used, k_used);
    }
};

// The same lists without their distances, a quarter of the memory (4 bytes a
// neighbour instead of 16): what the approximate levels keep for 4 M points.
struct KnnIndices {
    uint32_t k_used = 0;
    // Not zeroed when sized (128 MiB at 4 M points, unpolled): every list is written.
    std::vector<uint32_t, UnwrittenOnResize<uint32_t>> indices;

    std::span<const uint32_t> of(uint32_t i) const {
        return std::span<const uint32_t>(indices).subspan(size_t(i) * k_used, k_used);
    }
};

// |p - q|^2 as the k-NN ranks points: a distance recomputed from a neighbour's
// index with it, sqrt(squared_distance(points[j], points[i])), is the k-NN's bit for bit.
inline double squared_distance(const glm::dvec3& p, const glm::dvec3& q) {
    const glm::dvec3 d = p - q;
    return d.x * d.x + d.y * d.y + d.z * d.z;
}

// The k nearest other points of every point (Euclidean).
// A stop (bake_stop.h) leaves the lists partial: the caller asks it and drops them.
KnnResult k_nearest_neighbors(std::span<const glm::dvec3> points, uint32_t k, const BakeStop* stop = nullptr);
KnnIndices k_nearest_indices(std::span<const glm::dvec3> points, uint32_t k, const BakeStop* stop = nullptr);

// Every pair u < v with |p_u - p_v| + offset[u] + offset[v] < -tolerance,
// sorted. The kd-tree keeps each subtree's smallest offset, so a subtree whose
// nearest possible point already fails the test is skipped.
// A stop (bake_stop.h) leaves the pairs partial: the caller asks it and drops them.
std::vector<std::pair<uint32_t, uint32_t>> pairs_below_negative_offsets(
    std::span<const glm::dvec3> points, std::span<const double> offset, double tolerance,
    const BakeStop* stop = nullptr);

}  // namespace lc::bake
