#pragma once
// An LBVH built and written by every rank of an MPI bake, none holding the
// whole light set: the lights spread by space (morton_partition.h), each rank
// merges the whole subtrees within its share (lbvh_units.h), rank 0 builds
// the top over their roots and numbers every node in the one-process
// breadth-first order (lbvh_top.h), and each rank writes its own nodes'
// records into the result channel file at those indices (pwrite), rank 0 the
// count and the top. The file is byte for byte what export_light_tree and
// the result channel would write in one process, at any rank count.
//
// What travels: 80 bytes a light that changes rank; a few hundred bytes per
// subtree to rank 0 and 4 bytes per subtree depth back. The file must be one
// file for every rank: one machine, or a shared filesystem for the job folder.
#include <cstdint>
#include <filesystem>

#include "lightcuts/result.h"
#include "lightmass_server/mpi/rank/morton_partition.h"
#include "lightmass_server/mpi/rank/rank_bake.h"
#include "lightmass_server/builders/tree_builder.h"

namespace lc::bake {

// Collective. Rank 0 returns the build's report once `tree_file` (the result
// channel) is complete; the other ranks return an empty report.
Result<BuildReport> build_split_lbvh(OwnedLights mine, const BuildOptions& options,
                                     const std::filesystem::path& tree_file, const ProgressFn& progress,
                                     RankStats& stats);

}  // namespace lc::bake
