#pragma once
// One bake's share on one MPI rank (run by lightmass_rank). Every rank makes
// its index ranges of the area-light samples, the environment's strata and the
// VPL paths (counter-based draws: the same lights at any rank count), or
// shoots radiosity into its blocks of receiver patches (radiosity_parts.h);
// rank 0 gathers the lights in rank order, adds the scene's lights, and builds
// the tree, as run_bake does in one process.
#include <cstdint>
#include <optional>

#include "lightcuts/result.h"
#include "lightmass_server/mpi/rank_job.h"

namespace lc::bake {

struct RankStats {
    uint64_t lights_made = 0;  // by this rank, before the gather
    uint64_t bytes_sent = 0;   // to the other ranks in the gathers and the merges
};

// Rank 0 returns the tree; the other ranks return nullopt once their share is sent.
Result<std::optional<BuildResult>> bake_share(const RankJob& job, int rank, int ranks,
                                              const ProgressFn& progress, RankStats& stats);

}  // namespace lc::bake
