#include "lightmass_server/mpi/rank/remote_subtrees.h"

#include <limits>

#include "lightmass_server/mpi/rank/mpi_transfer.h"

namespace lc::bake {
namespace {

constexpr uint64_t kServiceOver = std::numeric_limits<uint64_t>::max();

}  // namespace

LbvhRemoteMerges subtrees_over_ranks(int ranks, std::span<const SceneLight> lights) {
    LbvhRemoteMerges remote;
    remote.parts = uint32_t(ranks);
    remote.send = [lights](uint32_t part, const std::vector<std::span<const LbvhKey>>& subtrees) -> Status {
        std::vector<uint64_t> sizes;
        std::vector<LbvhKey> keys;
        for (const auto& subtree : subtrees) {
            sizes.push_back(subtree.size());
            keys.insert(keys.end(), subtree.begin(), subtree.end());
        }
        std::vector<SceneLight> their_lights;
        their_lights.reserve(keys.size());
        for (const LbvhKey& key : keys) their_lights.push_back(lights[key.leaf]);
        const uint64_t count = sizes.size();
        MPI_Send(&count, 1, MPI_UINT64_T, int(part), 0, MPI_COMM_WORLD);
        send_bytes(sizes.data(), sizes.size() * sizeof(uint64_t), int(part));
        send_bytes(keys.data(), keys.size() * sizeof(LbvhKey), int(part));
        send_bytes(their_lights.data(), their_lights.size() * sizeof(SceneLight), int(part));
        return Ok{};
    };
    remote.receive = [](uint32_t part) -> Result<std::vector<std::vector<BuildNode>>> {
        const std::vector<uint64_t> sizes = receive_vector<uint64_t>(int(part));
        const std::vector<BuildNode> nodes = receive_vector<BuildNode>(int(part));
        std::vector<std::vector<BuildNode>> subtrees;
        size_t at = 0;
        for (uint64_t size : sizes) {
            if (at + size > nodes.size())
                return make_error("rank " + std::to_string(part) + " sent too few nodes");
            subtrees.emplace_back(nodes.begin() + ptrdiff_t(at), nodes.begin() + ptrdiff_t(at + size));
            at += size;
        }
        return subtrees;
    };
    return remote;
}

void end_subtree_service(int ranks) {
    for (int rank = 1; rank < ranks; ++rank)
        MPI_Send(&kServiceOver, 1, MPI_UINT64_T, rank, 0, MPI_COMM_WORLD);
}

Status serve_subtrees(const BuildOptions& options, RankStats& stats) {
    for (;;) {
        uint64_t count = 0;
        MPI_Recv(&count, 1, MPI_UINT64_T, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (count == kServiceOver) return Ok{};
        const std::vector<uint64_t> sizes = receive_vector<uint64_t>(0);
        const std::vector<LbvhKey> keys = receive_vector<LbvhKey>(0);
        const std::vector<SceneLight> lights = receive_vector<SceneLight>(0);
        std::vector<uint64_t> merged_sizes;
        std::vector<BuildNode> merged;
        size_t at = 0;
        for (uint64_t size : sizes) {
            if (at + size > keys.size() || keys.size() != lights.size())
                return make_error("rank 0 sent a bad subtree");
            Result<std::vector<BuildNode>> nodes = merge_lbvh_subtree(
                std::span(keys).subspan(at, size), std::span(lights).subspan(at, size), options);
            if (!nodes) return nodes.failure();
            merged_sizes.push_back(nodes->size());
            merged.insert(merged.end(), nodes->begin(), nodes->end());
            at += size;
        }
        send_bytes(merged_sizes.data(), merged_sizes.size() * sizeof(uint64_t), 0);
        send_bytes(merged.data(), merged.size() * sizeof(BuildNode), 0);
        stats.bytes_sent += merged.size() * sizeof(BuildNode);
    }
}

}  // namespace lc::bake
