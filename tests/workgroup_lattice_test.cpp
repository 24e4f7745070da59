// Regions dispatched as one lattice of workgroups (workgroup_lattice.h): the
// tile-strided reference's tiles are one; anything else is not.
#include "editor_client/render/gpu/workgroup_lattice.h"

#include <gtest/gtest.h>

#include <vector>

#include "editor_client/render/pixel_stride.h"

namespace lc::client {
namespace {

TEST(WorkgroupLattice, AStridedReferencesTilesAreOneLattice) {
    for (uint32_t stride : {2u, 4u, 8u}) {
        Result<std::vector<PixelRegion>> tiles = strided_tiles(256, 128, 8, stride);
        ASSERT_TRUE(tiles.ok()) << tiles.error();
        std::optional<WorkgroupLattice> lattice = workgroup_lattice(*tiles, 8);
        ASSERT_TRUE(lattice) << "stride " << stride;
        EXPECT_EQ(lattice->step, stride);
        EXPECT_EQ(lattice->origin_x, stride / 2);
        EXPECT_EQ(lattice->origin_y, stride / 2);
        EXPECT_EQ(lattice->count_x, 256 / 8 / stride);
        EXPECT_EQ(lattice->count_y, 128 / 8 / stride);
        // Every workgroup of the grid lands on its tile, in order.
        for (size_t k = 0; k < tiles->size(); ++k) {
            const uint32_t i = uint32_t(k % lattice->count_x), j = uint32_t(k / lattice->count_x);
            EXPECT_EQ((*tiles)[k].x, (lattice->origin_x + i * lattice->step) * 8);
            EXPECT_EQ((*tiles)[k].y, (lattice->origin_y + j * lattice->step) * 8);
        }
    }
}

TEST(WorkgroupLattice, OneColumnIsALattice) {
    const std::vector<PixelRegion> column = {{16, 0, 8, 8}, {16, 24, 8, 8}, {16, 48, 8, 8}};
    std::optional<WorkgroupLattice> lattice = workgroup_lattice(column, 8);
    ASSERT_TRUE(lattice);
    EXPECT_EQ(lattice->step, 3u);
    EXPECT_EQ(lattice->count_x, 1u);
    EXPECT_EQ(lattice->count_y, 3u);
}

TEST(WorkgroupLattice, OtherRegionsAreDispatchedOneByOne) {
    const std::vector<PixelRegion> whole = {{0, 0, 256, 256}};
    EXPECT_FALSE(workgroup_lattice(whole, 8)) << "one region";
    const std::vector<PixelRegion> wide = {{0, 0, 16, 8}, {32, 0, 16, 8}};
    EXPECT_FALSE(workgroup_lattice(wide, 8)) << "tiles of two workgroups";
    const std::vector<PixelRegion> unaligned = {{4, 0, 8, 8}, {20, 0, 8, 8}};
    EXPECT_FALSE(workgroup_lattice(unaligned, 8)) << "not on workgroup boundaries";
    const std::vector<PixelRegion> uneven = {{0, 0, 8, 8}, {16, 0, 8, 8}, {40, 0, 8, 8}};
    EXPECT_FALSE(workgroup_lattice(uneven, 8)) << "unequal steps";
    const std::vector<PixelRegion> ragged = {{0, 0, 8, 8}, {16, 0, 8, 8}, {0, 16, 8, 8}};
    EXPECT_FALSE(workgroup_lattice(ragged, 8)) << "a short last row";
    const std::vector<PixelRegion> rows_apart = {{0, 0, 8, 8}, {16, 0, 8, 8}, {0, 32, 8, 8}, {16, 32, 8, 8}};
    EXPECT_FALSE(workgroup_lattice(rows_apart, 8)) << "rows further apart than columns";
    const std::vector<PixelRegion> backwards = {{16, 0, 8, 8}, {0, 0, 8, 8}};
    EXPECT_FALSE(workgroup_lattice(backwards, 8));
    EXPECT_FALSE(workgroup_lattice(std::vector<PixelRegion>{}, 8));
}

}  // namespace
}  // namespace lc::client
