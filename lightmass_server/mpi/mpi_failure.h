#pragma once
// An MPI launch that failed, in one line a user can act on: the launcher's
// known refusals (too few slots, running as root, no rank program) name the
// lightmass_server flag (or, for a spawned server, editor_client's
// --server-arg) that fixes them. Unknown failures: empty, and the caller
// reports the log's tail.
#include <cstdint>
#include <string>

namespace lc::bake {

std::string explain_mpi_failure(const std::string& launcher_log, uint32_t ranks);

}  // namespace lc::bake
