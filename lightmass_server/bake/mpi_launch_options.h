#pragma once
// How the server starts the MPI job of a bake that asks for ranks
// (BakeRequest.ranks): `launcher -n N [args...] [--hostfile F] rank_program --job DIR`.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lc::bake {

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
};

}  // namespace lc::bake
