#include "lightmass_server/mpi/mpi_failure.h"

namespace lc::bake {
namespace {

bool says(const std::string& log, const char* phrase) { return log.find(phrase) != std::string::npos; }

// How a flag reaches a server that editor_client --spawn-server started.
std::string spawned(const std::string& server_flag) {
    return " (a server started by editor_client --spawn-server: --server-arg=" + server_flag + ")";
}

}  // namespace

std::string explain_mpi_failure(const std::string& log, uint32_t ranks) {
    const std::string n = std::to_string(ranks);
    if (says(log, "not enough slots"))
        return "MPI: mpirun found fewer slots than the " + n +
               " ranks asked for: pass lightmass_server --mpi-oversubscribe on, or list machines with "
               "--mpi-hostfile FILE" +
               spawned("--mpi-oversubscribe=on");
    if (says(log, "attempt to run as root"))
        return "MPI: mpirun refuses to run as root: run lightmass_server as another user (packaging/ runs it as "
               "'lightcuts'), or pass --mpi-arg=--allow-run-as-root" +
               spawned("--mpi-arg=--allow-run-as-root");
    if (says(log, "was unable to find the specified executable") || says(log, "could not access or execute"))
        return "MPI: mpirun could not start the rank program: pass lightmass_server --mpi-rank-program PATH "
               "(every rank's machine needs it at that path)" +
               spawned("--mpi-rank-program=PATH");
    return "";
}

}  // namespace lc::bake
