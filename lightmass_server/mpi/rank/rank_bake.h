#pragma once
// One bake's share on one MPI rank (run by lightmass_rank). Every rank makes
// its index ranges of the area-light samples, the environment's strata and the
// VPL paths (counter-based draws: the same lights at any rank count), or
// shoots radiosity into its blocks of receiver patches (radiosity_parts.h);
// rank 0 gathers the lights in rank order, adds the scene's lights, and builds
// the tree, as run_bake does in one process.
#include <cstdint>
#include <filesystem>
#include <optional>

#include "lightcuts/result.h"
#include "lightmass_server/mpi/rank_job.h"
#include "protocol/channel_records.h"

namespace lc::bake {

// The VPLs a bake over ranks may make when no rank gathers them (an LBVH
// built over the ranks): the tree's own limit. A bake whose builder gathers
// every light on rank 0 keeps the one-process cap, kMaxIndirectLights.
inline constexpr uint64_t kMaxRankBakeIndirectLights = kMaxSceneLights;  // 16,777,216

struct RankStats {
    uint64_t lights_made = 0;   // by this rank, before the gather
    uint64_t bytes_sent = 0;    // to the other ranks in the gathers and the merges
    bool tree_written = false;  // rank 0: the ranks wrote result.lcut themselves (split_lbvh.h)
};

// Rank 0 returns the tree; the other ranks return nullopt once their share is
// sent. An LBVH is built and written over the ranks into `tree_file`
// (split_lbvh.h): rank 0 then returns an empty tree and sets stats.tree_written.
Result<std::optional<BuildResult>> bake_share(const RankJob& job, int rank, int ranks,
                                              const std::filesystem::path& tree_file,
                                              const ProgressFn& progress, RankStats& stats);

}  // namespace lc::bake
