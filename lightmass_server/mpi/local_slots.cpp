#include "lightmass_server/mpi/local_slots.h"

#include <algorithm>

namespace lc::bake {

LocalLaunch local_launch(const MpiLaunchOptions& mpi, uint32_t ranks, uint32_t cores) {
    LocalLaunch launch;
    const auto& args = mpi.launcher_args;
    if (mpi.oversubscribe == "off" || std::find(args.begin(), args.end(), "--oversubscribe") != args.end())
        return launch;
    const bool local = mpi.hostfile.empty();
    if (mpi.oversubscribe == "on") {
        launch.extra_args = {"--oversubscribe"};
        launch.note = "mpi: " + std::to_string(ranks) + " ranks, oversubscribed (--mpi-oversubscribe on)";
    } else if (local && ranks > cores) {
        launch.extra_args = {"--oversubscribe"};
        launch.note = "mpi: " + std::to_string(ranks) + " ranks on this machine's " + std::to_string(cores) +
                      " cores: oversubscribed (--mpi-oversubscribe off refuses instead)";
    }
    return launch;
}

}  // namespace lc::bake
