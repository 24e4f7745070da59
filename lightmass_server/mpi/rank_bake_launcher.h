#pragma once
// The coordinator's side of a bake over MPI ranks, in the role of Swarm's
// coordinator: the server writes the bake's inputs into a job folder,
// launches `mpirun -n N ... lightmass_rank --job DIR` in a process group of
// its own, forwards rank 0's progress, and adopts the tree file rank 0 wrote
// (BuildResult::channel_file: checked a chunk at a time, then streamed to the
// client from disk, never decoded here).
// A rank that dies ends the job (mpirun aborts it): the bake fails with the
// job's exit status and log, and the server goes on. Cancelling (the progress
// callback returns false) signals the whole process group, so every rank stops.
#include "lightcuts/result.h"
#include "lightmass_server/bake/bake_pipeline.h"

namespace lc::bake {

// `inputs.ranks` >= 1; more than `inputs.mpi.max_ranks` is refused.
Result<BuildResult> run_bake_on_ranks(const BakeInputs& inputs, const ProgressFn& progress);

}  // namespace lc::bake
