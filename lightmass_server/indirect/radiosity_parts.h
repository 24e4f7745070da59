#pragma once
// Radiosity split over processes (the MPI ranks of mpi/rank/): the patches
// fall into fixed blocks of kRadiosityBlockPatches, and part p of P updates
// the receivers of its share of the blocks (share_of over the block count).
// Every shot, each part sums its blocks' unshot power (in patch order inside
// a block) and finds its brightest unshot patch; one all-gather hands every
// part all the parts' summaries, and each adds the block sums in block order
// and takes the first brightest patch. The blocks do not depend on the part
// count, and one process sums the same blocks the same way, so the solve is
// byte-identical at any part count and to the solve in one process.
#include <cstdint>
#include <functional>
#include <vector>

#include "lightcuts/result.h"
#include "lightmass_server/builders/index_range.h"

namespace lc::bake {

// Patches per block: the unit of the unshot-power sum and of a part's share.
inline constexpr uint64_t kRadiosityBlockPatches = 256;

inline uint64_t radiosity_block_count(uint64_t patches) {
    return (patches + kRadiosityBlockPatches - 1) / kRadiosityBlockPatches;
}

// The blocks part `part` of `parts` owns.
inline IndexRange radiosity_blocks_of(uint64_t patches, uint32_t part, uint32_t parts) {
    return share_of(radiosity_block_count(patches), part, parts);
}

// The receivers (patch indices) part `part` of `parts` owns.
inline IndexRange radiosity_receivers_of(uint64_t patches, uint32_t part, uint32_t parts) {
    const IndexRange blocks = radiosity_blocks_of(patches, part, parts);
    return {std::min(patches, blocks.begin * kRadiosityBlockPatches),
            std::min(patches, blocks.end * kRadiosityBlockPatches)};
}

// A part whose solve fails or stops (its BakeStop) returns while the others
// wait in the next all-gather: the caller ends them (lightmass_rank aborts
// the whole job on any rank's error; the coordinator stops the job on cancel).
struct RadiosityParts {
    uint32_t part = 0, parts = 1;
    // Every part's `mine`, concatenated in part order; called once per shot
    // by every part (a collective: all parts call it the same number of times).
    // `sizes` holds every part's count, known to all beforehand (5 + its
    // blocks), so one collective moves the summaries without their sizes first.
    std::function<Result<std::vector<double>>(const std::vector<double>& mine, const std::vector<int>& sizes)>
        all_gather;
};

}  // namespace lc::bake
