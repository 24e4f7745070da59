#include "lightmass_server/mpi/rank/morton_partition.h"

#include <mpi.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <limits>
#include <string>

#include "lightmass_server/builders/cluster_attributes.h"

namespace lc::bake {
namespace {

// Buckets per light group: the codes' top 15 bits (5 per axis). A bucket is
// the unit of the spread, so one bucket's lights always land on one rank.
constexpr int kBucketBits = 15;
constexpr size_t kBuckets = kLightGroupCount << kBucketBits;

struct Shipped {
    SceneLight light;
    uint32_t leaf;
};

struct Coded {
    uint64_t code;
    uint32_t leaf, at;
    uint8_t group;
    bool operator<(const Coded& o) const {
        if (group != o.group) return group < o.group;
        return code < o.code || (code == o.code && leaf < o.leaf);
    }
};

size_t bucket_of(size_t group, uint64_t code) {
    return (group << kBucketBits) | size_t(code >> (63 - kBucketBits));
}

// Every group's curve over the bounds of its lights on every rank (min and max are exact: any order).
std::array<LbvhCurve, kLightGroupCount> reduced_curves(const std::vector<SceneLight>& lights) {
    std::array<double, 3 * kLightGroupCount> lo, hi;
    lo.fill(std::numeric_limits<double>::max());
    hi.fill(std::numeric_limits<double>::lowest());
    for (const SceneLight& light : lights) {
        const size_t g = light_group(light);
        const glm::dvec3 p = light_point(light);
        for (int a = 0; a < 3; ++a) {
            lo[3 * g + size_t(a)] = std::min(lo[3 * g + size_t(a)], p[a]);
            hi[3 * g + size_t(a)] = std::max(hi[3 * g + size_t(a)], p[a]);
        }
    }
    MPI_Allreduce(MPI_IN_PLACE, lo.data(), int(lo.size()), MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, hi.data(), int(hi.size()), MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    std::array<LbvhCurve, kLightGroupCount> curves;
    for (size_t g = 0; g < kLightGroupCount; ++g) {
        if (lo[3 * g] > hi[3 * g]) continue;  // no light of this group anywhere
        curves[g] =
            lbvh_curve({lo[3 * g], lo[3 * g + 1], lo[3 * g + 2]}, {hi[3 * g], hi[3 * g + 1], hi[3 * g + 2]});
    }
    return curves;
}

// Each bucket's rank: the buckets in order, cut where the running count passes r * n / N.
std::vector<uint16_t> bucket_ranks(const std::vector<uint64_t>& histogram, uint64_t total, int ranks) {
    std::vector<uint16_t> rank_of(histogram.size());
    uint64_t before = 0;
    for (size_t b = 0; b < histogram.size(); ++b) {
        rank_of[b] = uint16_t(
            total == 0 ? 0 : std::min<uint64_t>(uint64_t(ranks - 1), before * uint64_t(ranks) / total));
        before += histogram[b];
    }
    return rank_of;
}

// The lights by destination rank, then one all-to-all; returns what arrived.
Result<std::vector<Shipped>> exchange(OwnedLights& mine, const std::vector<size_t>& destination, int ranks,
                                      uint64_t& bytes_sent) {
    std::vector<int> send_counts(size_t(ranks), 0), send_at(size_t(ranks), 0);
    std::vector<uint64_t> per_rank(size_t(ranks), 0);
    for (size_t d : destination) ++per_rank[d];
    const size_t count = mine.lights.size();
    std::vector<Shipped> outgoing(count);
    std::vector<uint64_t> cursor(size_t(ranks), 0);
    for (int r = 1; r < ranks; ++r) cursor[size_t(r)] = cursor[size_t(r - 1)] + per_rank[size_t(r - 1)];
    for (size_t i = 0; i < count; ++i)
        outgoing[cursor[destination[i]]++] = Shipped{mine.lights[i], mine.index[i]};
    mine = OwnedLights{};
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    for (int r = 0, at = 0; r < ranks; ++r) {
        const uint64_t bytes = per_rank[size_t(r)] * sizeof(Shipped);
        if (bytes + uint64_t(at) > uint64_t(std::numeric_limits<int>::max()))
            return make_error("too large: " + std::to_string(count) +
                              " lights exceed one MPI all-to-all's int counts; use more ranks");
        send_counts[size_t(r)] = int(bytes);
        send_at[size_t(r)] = at;
        at += int(bytes);
        if (r != rank) bytes_sent += bytes;
    }
    std::vector<int> receive_counts(static_cast<size_t>(ranks), 0), receive_at(static_cast<size_t>(ranks), 0);
    MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    uint64_t incoming = 0;
    for (int r = 0; r < ranks; ++r) {
        if (incoming > uint64_t(std::numeric_limits<int>::max()))
            return make_error(
                "too large: this rank's share exceeds one MPI all-to-all's int counts; use more ranks");
        receive_at[size_t(r)] = int(incoming);
        incoming += uint64_t(receive_counts[size_t(r)]);
    }
    std::vector<Shipped> arrived(incoming / sizeof(Shipped));
    MPI_Alltoallv(outgoing.data(), send_counts.data(), send_at.data(), MPI_BYTE, arrived.data(),
                  receive_counts.data(), receive_at.data(), MPI_BYTE, MPI_COMM_WORLD);
    return arrived;
}

}  // namespace

Result<SortedShare> spread_by_space(OwnedLights mine, uint64_t& bytes_sent) {
    int ranks = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    if (mine.lights.size() != mine.index.size())
        return make_error("a rank's lights and their indices differ in number");
    const std::array<LbvhCurve, kLightGroupCount> curves = reduced_curves(mine.lights);
    std::vector<uint64_t> histogram(kBuckets, 0);
    std::vector<size_t> bucket(mine.lights.size());
    for (size_t i = 0; i < mine.lights.size(); ++i) {
        const size_t g = light_group(mine.lights[i]);
        bucket[i] = bucket_of(g, lbvh_code(mine.lights[i], curves[g]));
        ++histogram[bucket[i]];
    }
    SortedShare share;
    share.total_lights = mine.lights.size();
    MPI_Allreduce(MPI_IN_PLACE, &share.total_lights, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, histogram.data(), int(histogram.size()), MPI_UINT64_T, MPI_SUM,
                  MPI_COMM_WORLD);
    const std::vector<uint16_t> rank_of = bucket_ranks(histogram, share.total_lights, ranks);
    histogram = {};
    for (size_t& b : bucket) b = rank_of[b];  // now each light's destination
    Result<std::vector<Shipped>> arrived = exchange(mine, bucket, ranks, bytes_sent);
    if (!arrived) return arrived.failure();
    bucket = {};

    std::vector<Coded> order(arrived->size());
    for (size_t i = 0; i < order.size(); ++i) {
        const size_t g = light_group((*arrived)[i].light);
        order[i] =
            Coded{lbvh_code((*arrived)[i].light, curves[g]), (*arrived)[i].leaf, uint32_t(i), uint8_t(g)};
    }
    tbb::parallel_sort(order.begin(), order.end());  // a strict total order: deterministic
    share.keys.resize(order.size());
    share.lights.resize(order.size());
    for (size_t k = 0; k < order.size(); ++k) {
        share.keys[k] = LbvhKey{order[k].code, order[k].leaf};
        share.lights[k] = (*arrived)[order[k].at].light;
        ++share.group_begin[order[k].group + 1];
    }
    for (size_t g = 0; g < kLightGroupCount; ++g) share.group_begin[g + 1] += share.group_begin[g];
    return share;
}

}  // namespace lc::bake
