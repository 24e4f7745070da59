#pragma once
// An LBVH's lights spread over MPI ranks by space (split_lbvh.h): every rank
// codes its lights on their group's Z-order curve (bounds reduced over the
// ranks, so the codes are the one-process codes), then each light travels to
// the rank that owns its (group, code prefix) bucket. The buckets go to the
// ranks in order by a histogram summed over the ranks, about n / N lights
// each, so rank r ends with a contiguous range of the global order by
// (group, code, input index): the order the one-process build sorts into.
#include <array>
#include <cstdint>
#include <vector>

#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/lbvh_builder.h"
#include "lightmass_server/tree_builder.h"

namespace lc::bake {

// A rank's lights before the spread, with their indices in the tree's input order.
struct OwnedLights {
    std::vector<SceneLight> lights;
    std::vector<uint32_t> index;
};

// A rank's lights after it: sorted by (group, code, leaf).
struct SortedShare {
    std::vector<LbvhKey> keys;       // leaf: the global input index
    std::vector<SceneLight> lights;  // lights[k] is keys[k]'s
    // Group g's keys are [group_begin[g], group_begin[g + 1]).
    std::array<uint32_t, kLightGroupCount + 1> group_begin{};
    uint64_t total_lights = 0;  // over every rank
};

// Collective: every rank calls it. `mine` is consumed; adds what this rank
// sent to the others (80 bytes a light that changes rank) to `bytes_sent`.
Result<SortedShare> spread_by_space(OwnedLights mine, uint64_t& bytes_sent);

}  // namespace lc::bake
