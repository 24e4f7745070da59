#include "lightmass_server/mpi/mpi_flags.h"

namespace lc::bake {

void add_mpi_flags(CLI::App& app, MpiLaunchOptions& mpi) {
    app.add_option("--mpi-launcher", mpi.launcher,
                   "Command that starts a bake's MPI job (BakeRequest.ranks > 0)")
        ->capture_default_str();
    app.add_option("--mpi-arg", mpi.launcher_args,
                   "An argument for the launcher, before the program (repeat: --mpi-arg=--oversubscribe)")
        ->allow_extra_args(false);
    app.add_option("--mpi-hostfile", mpi.hostfile, "The launcher's host file: the machines the ranks run on");
    app.add_option("--mpi-max-ranks", mpi.max_ranks,
                   "Most ranks one bake may ask for (0: no multi-rank bakes)")
        ->capture_default_str();
    app.add_option("--mpi-rank-program", mpi.rank_program,
                   "The rank executable (default: lightmass_rank beside this server)");
    app.add_option(
        "--mpi-work-dir", mpi.work_dir,
        "Folder for the bakes' job files; every rank's machine must see it (default: the temp folder)");
    app.add_option("--mpi-oversubscribe", mpi.oversubscribe,
                   "auto: a launch on this machine alone (no --mpi-hostfile) with more ranks than cores adds "
                   "--oversubscribe, and says so in the log; on: always; off: never (mpirun then refuses)")
        ->check(CLI::IsMember({"auto", "on", "off"}))
        ->capture_default_str();
    app.add_option("--mpi-launch-seconds", mpi.launch_seconds,
                   "A multi-rank bake fails unless every rank has started within this many seconds")
        ->capture_default_str()
        ->check(CLI::Range(1u, 86400u));
    app.add_flag("--mpi-keep-jobs", mpi.keep_job_dirs, "Leave each multi-rank bake's job folder behind");
}

}  // namespace lc::bake
