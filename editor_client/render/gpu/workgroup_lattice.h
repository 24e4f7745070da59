#pragma once
// Regions that are single workgroups on a regular lattice (a tile-strided
// reference's tiles, pixel_stride.h) dispatched as one grid: lavapipe runs a
// dispatch's workgroups on all its threads but each dispatch after the
// previous one, so one dispatch a tile kept a 2-core machine half idle and
// made the strided reference's scaled time 1.9x the full frame's.
#include <cstdint>
#include <optional>
#include <span>

#include "editor_client/render/gpu/pixel_region.h"

namespace lc::client {

// Workgroup (i, j) of a count_x x count_y dispatch lights the workgroup
// (origin_x + i * step, origin_y + j * step) of the image (in workgroups).
struct WorkgroupLattice {
    uint32_t origin_x = 0;
    uint32_t origin_y = 0;
    uint32_t step = 1;
    uint32_t count_x = 0;
    uint32_t count_y = 0;
};

// The lattice `regions` form, in their row-major order, when each is one
// `workgroup_size` square workgroup and there are at least two; otherwise
// std::nullopt (dispatch them one by one).
std::optional<WorkgroupLattice> workgroup_lattice(std::span<const PixelRegion> regions,
                                                  uint32_t workgroup_size);

}  // namespace lc::client
