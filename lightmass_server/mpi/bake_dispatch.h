#pragma once
// Where a bake runs: in this process (bake/bake_pipeline.h) or over MPI ranks
// (rank_bake_launcher.h) when its request asks for ranks. The one entry the
// connection and the tests call, so bake/ never needs to know about mpi/.
#include "lightmass_server/bake/bake_pipeline.h"

namespace lc::bake {

// The tree of `inputs`, baked over inputs.ranks MPI ranks, or in process when 0.
Result<BuildResult> run_bake(const BakeInputs& inputs, const ProgressFn& progress);

}  // namespace lc::bake
