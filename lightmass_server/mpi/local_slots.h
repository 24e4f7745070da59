#pragma once
// What the server adds to a local MPI launch by itself: Open MPI refuses more
// ranks than the machine has cores ("not enough slots") unless told to
// oversubscribe. A launch on this machine alone (no hostfile) with more ranks
// than cores oversubscribes under --mpi-oversubscribe auto, and says so.
#include <cstdint>
#include <string>
#include <vector>

#include "lightmass_server/bake/mpi_launch_options.h"

namespace lc::bake {

struct LocalLaunch {
    std::vector<std::string> extra_args;  // before the launcher's own --mpi-arg values
    std::string note;                     // for the log and the bake's census; empty: nothing added
};

// `cores`: this machine's (std::thread::hardware_concurrency, passed in so tests pick it).
LocalLaunch local_launch(const MpiLaunchOptions& mpi, uint32_t ranks, uint32_t cores);

}  // namespace lc::bake
