#pragma once
// How the server starts the MPI job of a bake that asks for ranks
// (BakeRequest.ranks): `launcher -n N [args...] [--hostfile F] rank_program --job DIR`.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace lc::bake {

class HostRoster;  // mpi/host_roster.h

struct MpiLaunchOptions {
    std::string launcher = "mpirun";
    // Passed to the launcher before the program, e.g. --oversubscribe, --mca btl self,tcp.
    std::vector<std::string> launcher_args;
    std::filesystem::path hostfile;      // empty: the launcher's default (this machine)
    // empty: lightmass_rank beside the server's executable, else where the package installs it
    // (rank_program.h).
    std::filesystem::path rank_program;
    std::vector<std::string> rank_args;  // after --job DIR (the tests' fault injection)
    // A bake asking for more ranks is refused; 0 refuses every multi-rank bake.
    uint32_t max_ranks = 16;
    // Each multi-rank bake gets a job folder here (the ranks must see it: on
    // several machines, a shared file system); empty: the system's temp folder.
    std::filesystem::path work_dir;
    bool keep_job_dirs = false;  // for debugging: leave each bake's job folder behind
    // "auto": a launch on this machine alone (no hostfile) with more ranks than
    // its cores adds --oversubscribe, and says so; "on": always; "off": never.
    std::string oversubscribe = "auto";
    // Every rank must have started within this many seconds, or the bake fails
    // (a host that never answers would otherwise hold it until --max-bake-seconds).
    unsigned launch_seconds = 60;
    // The host file's hosts lost by earlier bakes, left out of the next ones;
    // null: every bake gets the whole host file.
    std::shared_ptr<HostRoster> lost_hosts;
};

}  // namespace lc::bake
