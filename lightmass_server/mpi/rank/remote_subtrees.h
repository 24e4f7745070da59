#pragma once
// The LBVH's subtrees over MPI ranks (lbvh_builder.h's LbvhRemoteMerges):
// rank 0 sends rank p the keys and lights of part p's subtrees and receives
// their merged nodes; the other ranks serve such requests until rank 0 says
// the build is over. What travels: 12 bytes per key and 80 per light to a
// rank, 160 per merged node back.
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/result.h"
#include "lightmass_server/lbvh_builder.h"
#include "lightmass_server/mpi/rank/rank_bake.h"

namespace lc::bake {

// Rank 0's side: parts = ranks, part p on rank p; `lights` is the build's input.
LbvhRemoteMerges subtrees_over_ranks(int ranks, std::span<const SceneLight> lights);
// Rank 0, after the build (or its failure): every other rank stops serving.
void end_subtree_service(int ranks);
// Ranks 1..N-1: merges what rank 0 sends until it ends the service.
Status serve_subtrees(const BuildOptions& options, RankStats& stats);

}  // namespace lc::bake
