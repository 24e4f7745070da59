#include "lightmass_server/mpi/bake_dispatch.h"

#include "lightmass_server/mpi/rank_bake_launcher.h"

namespace lc::bake {

Result<BuildResult> run_bake(const BakeInputs& inputs, const ProgressFn& progress) {
    if (inputs.ranks > 0) return run_bake_on_ranks(inputs, progress);
    return run_bake_in_process(inputs, progress);
}

}  // namespace lc::bake
