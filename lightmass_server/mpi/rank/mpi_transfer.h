#pragma once
// The collectives a bake over ranks needs, over MPI_BYTE: rank 0's job bytes
// to every rank, every rank's share of a sampler's output back to rank 0 in
// rank order (so the concatenation is the single process's output), and the
// radiosity's small per-shot summaries to every rank.
#include <mpi.h>

#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "lightcuts/result.h"

namespace lc::bake {

// MPI counts are ints: larger buffers travel in pieces of this many bytes.
inline constexpr uint64_t kMpiPieceBytes = uint64_t{1} << 30;

// `bytes` is rank 0's on entry and everyone's on return.
inline void broadcast_bytes(std::vector<uint8_t>& bytes) {
    uint64_t size = bytes.size();
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    bytes.resize(size);
    for (uint64_t at = 0; at < size; at += kMpiPieceBytes) {
        MPI_Bcast(bytes.data() + at, int(std::min(kMpiPieceBytes, size - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
    }
}

// Rank 0 receives every rank's `mine`, concatenated in rank order; the other
// ranks get an empty vector. Adds the bytes this rank sent to `bytes_sent`.
template <typename T>
Result<std::vector<T>> gather_in_rank_order(const std::vector<T>& mine, uint64_t& bytes_sent) {
    static_assert(std::is_trivially_copyable_v<T>);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    const uint64_t my_bytes = mine.size() * sizeof(T);
    std::vector<uint64_t> sizes(size_t(ranks), 0);
    MPI_Gather(&my_bytes, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    uint64_t total = 0;
    for (uint64_t s : sizes) total += s;
    MPI_Bcast(&total, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    if (total > uint64_t(INT32_MAX))
        return make_error("a gather of " + std::to_string(total) + " bytes exceeds MPI's int counts");
    std::vector<int> counts(static_cast<size_t>(ranks)), offsets(static_cast<size_t>(ranks));
    for (int r = 0, at = 0; r < ranks; ++r) {
        counts[size_t(r)] = int(sizes[size_t(r)]);
        offsets[size_t(r)] = at;
        at += counts[size_t(r)];
    }
    std::vector<T> all(rank == 0 ? total / sizeof(T) : 0);
    MPI_Gatherv(mine.data(), int(my_bytes), MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, 0,
                MPI_COMM_WORLD);
    if (rank != 0) bytes_sent += my_bytes;
    return all;
}

// Every rank receives every rank's `mine`, concatenated in rank order.
template <typename T>
Result<std::vector<T>> gather_to_all(const std::vector<T>& mine, uint64_t& bytes_sent) {
    Result<std::vector<T>> all = gather_in_rank_order(mine, bytes_sent);
    if (!all) return all;
    std::vector<uint8_t> bytes(all->size() * sizeof(T));
    // Only rank 0 holds the gather; memcpy must not see another rank's empty (null) vector.
    if (!bytes.empty()) std::memcpy(bytes.data(), all->data(), bytes.size());
    broadcast_bytes(bytes);
    std::vector<T> out(bytes.size() / sizeof(T));
    if (!bytes.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
}

// Every rank receives every rank's `mine`, concatenated in rank order, with
// one MPI_Allgatherv: `sizes` (elements per rank, small) is known to every
// rank beforehand. Adds what this rank sent to the others to `bytes_sent`.
template <typename T>
Result<std::vector<T>> all_gather_known_sizes(const std::vector<T>& mine, const std::vector<int>& sizes,
                                              uint64_t& bytes_sent) {
    static_assert(std::is_trivially_copyable_v<T>);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    if (sizes.size() != size_t(ranks) || size_t(sizes[size_t(rank)]) != mine.size())
        return make_error("an all-gather's sizes do not match the ranks or this rank's share");
    std::vector<int> counts(sizes.size()), offsets(sizes.size());
    int total = 0;
    for (size_t r = 0; r < sizes.size(); ++r) {
        counts[r] = sizes[r] * int(sizeof(T));
        offsets[r] = total;
        total += counts[r];
    }
    std::vector<T> all(size_t(total) / sizeof(T));
    MPI_Allgatherv(mine.data(), counts[size_t(rank)], MPI_BYTE, all.data(), counts.data(), offsets.data(),
                   MPI_BYTE, MPI_COMM_WORLD);
    bytes_sent += uint64_t(counts[size_t(rank)]) * uint64_t(ranks - 1);
    return all;
}

// Where this rank's `mine` items sit among every rank's, in rank order.
struct ShareIndex {
    uint64_t before = 0;  // items of the ranks before this one
    uint64_t total = 0;   // items of every rank
};
inline ShareIndex index_of_share(uint64_t mine) {
    ShareIndex index;
    MPI_Exscan(&mine, &index.before, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) index.before = 0;  // MPI_Exscan leaves rank 0's undefined
    MPI_Allreduce(&mine, &index.total, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    return index;
}

// Point to point: a size, then the bytes in pieces.
inline void send_bytes(const void* data, uint64_t size, int to) {
    MPI_Send(&size, 1, MPI_UINT64_T, to, 0, MPI_COMM_WORLD);
    const auto* bytes = static_cast<const uint8_t*>(data);
    for (uint64_t at = 0; at < size; at += kMpiPieceBytes)
        MPI_Send(bytes + at, int(std::min(kMpiPieceBytes, size - at)), MPI_BYTE, to, 0, MPI_COMM_WORLD);
}

template <typename T>
std::vector<T> receive_vector(int from) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint64_t size = 0;
    MPI_Recv(&size, 1, MPI_UINT64_T, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::vector<T> out(size / sizeof(T));
    auto* bytes = reinterpret_cast<uint8_t*>(out.data());
    for (uint64_t at = 0; at < size; at += kMpiPieceBytes)
        MPI_Recv(bytes + at, int(std::min(kMpiPieceBytes, size - at)), MPI_BYTE, from, 0, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
    return out;
}

}  // namespace lc::bake
