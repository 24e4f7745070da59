#pragma once
// An LBVH's lights spread over MPI ranks by space (split_lbvh.h): every rank
// codes its lights on their group's Z-order curve (bounds reduced over the
// ranks, so the codes are the one-process codes), then each light travels to
// the rank that owns its (group, code prefix) bucket. The buckets go to the
// ranks in order by a histogram summed over the ranks, about n / N lights
// each, so rank r ends with a contiguous range of the global order by
// (group, code, input index): the order the one-process build sorts into.
#include <cstdint>
#include <vector>

#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/mpi/lbvh_units.h"

namespace lc::bake {

// A rank's lights before the spread, with their indices in the tree's input order.
struct OwnedLights {
    std::vector<SceneLight> lights;
    std::vector<uint32_t> index;
};

// Collective: every rank calls it. `mine` is consumed; adds what this rank
// sent to the others (84 bytes a light that changes rank) to `bytes_sent`.
Result<SortedShare> spread_by_space(OwnedLights mine, uint64_t& bytes_sent);

}  // namespace lc::bake
