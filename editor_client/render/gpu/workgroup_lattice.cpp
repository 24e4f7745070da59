#include "editor_client/render/gpu/workgroup_lattice.h"

namespace lc::client {

std::optional<WorkgroupLattice> workgroup_lattice(std::span<const PixelRegion> regions,
                                                  uint32_t workgroup_size) {
    if (regions.size() < 2 || workgroup_size == 0) return std::nullopt;
    for (const PixelRegion& r : regions)
        if (r.width != workgroup_size || r.height != workgroup_size || r.x % workgroup_size != 0 ||
            r.y % workgroup_size != 0)
            return std::nullopt;
    WorkgroupLattice lattice;
    lattice.origin_x = regions[0].x / workgroup_size;
    lattice.origin_y = regions[0].y / workgroup_size;
    // The step is the distance to the second region, along x (a row of
    // several) or along y (a single column).
    const PixelRegion& second = regions[1];
    if (second.y == regions[0].y && second.x > regions[0].x) {
        lattice.step = (second.x - regions[0].x) / workgroup_size;
        size_t row = 1;
        while (row < regions.size() && regions[row].y == regions[0].y) ++row;
        lattice.count_x = uint32_t(row);
    } else if (second.x == regions[0].x && second.y > regions[0].y) {
        lattice.step = (second.y - regions[0].y) / workgroup_size;
        lattice.count_x = 1;
    } else {
        return std::nullopt;
    }
    if (regions.size() % lattice.count_x != 0) return std::nullopt;
    lattice.count_y = uint32_t(regions.size() / lattice.count_x);
    for (size_t k = 0; k < regions.size(); ++k) {
        const uint64_t i = k % lattice.count_x, j = k / lattice.count_x;
        if (uint64_t(regions[k].x) != (lattice.origin_x + i * lattice.step) * workgroup_size ||
            uint64_t(regions[k].y) != (lattice.origin_y + j * lattice.step) * workgroup_size)
            return std::nullopt;
    }
    return lattice;
}

}  // namespace lc::client
