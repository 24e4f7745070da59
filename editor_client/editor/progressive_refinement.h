#pragma once
// The progressive editor's schedule: an image refines over many frames, coarse
// to fine, in tiles, each frame taking only as many tiles as fit its GPU
// budget, so that input and the panels are handled every frame however long a
// whole image takes (tens of seconds on lavapipe with shadow rays). A pass is
// one image size: first 1/divisor of the view's width and height, then the
// full size. The cost per pixel is learned from the GPU time of the last
// batches, so the tile count per frame follows what the scene costs.
#include <cstdint>
#include <optional>
#include <vector>

#include "editor_client/render/gpu/pixel_region.h"

namespace lc::client {

struct ProgressiveOptions {
    double frame_budget_ms = 30.0;   // GPU time a frame's tiles aim at
    // Largest tile side in pixels (rounded up to the alignment); a pass whose
    // learned cost puts one such tile over the budget uses smaller tiles.
    uint32_t tile_size = 16;
    uint32_t max_tiles_per_frame = 256;
};

// One frame's share of the refinement.
struct TileBatch {
    uint32_t pass = 0;     // 0-based index of the pass
    uint32_t divisor = 1;  // of the full width and height (1: full size)
    uint32_t width = 0;    // the pass's image size
    uint32_t height = 0;
    bool new_image = false;  // the pass's first batch: the G-buffer is drawn first
    std::vector<PixelRegion> tiles;

    uint64_t pixels() const;
};

class ProgressiveRefinement {
public:
    // `alignment`: tile origins fall on multiples of it (the compute workgroup size).
    ProgressiveRefinement(uint32_t width, uint32_t height, uint32_t alignment,
                          ProgressiveOptions options = {});

    // Starts again from the coarsest pass: passes at 1/coarse_divisor (skipped
    // when 1) and at full size.
    void restart(uint32_t coarse_divisor);
    // The next frame's tiles, or none when the image is complete.
    std::optional<TileBatch> next_batch();
    // After the GPU ran `batch`: its lighting and output time.
    void report(const TileBatch& batch, double gpu_ms);

    bool complete() const { return pass_ >= divisors_.size(); }
    uint32_t pass() const { return pass_; }  // passes done (== passes() when complete)
    uint32_t passes() const { return uint32_t(divisors_.size()); }
    // Tiles of the current pass handed out so far, in percent (100 when complete).
    double percent() const;
    // Learned GPU cost of one pixel (0 until a batch was reported).
    double ms_per_pixel() const { return ms_per_pixel_; }
    // Tiles the next batch takes: the budget over the learned cost of a tile.
    uint32_t tiles_per_frame() const;
    // The refining pass's tile side.
    uint32_t tile_side() const { return tile_side_; }

private:
    void start_pass();

    uint32_t width_;
    uint32_t height_;
    uint32_t alignment_;
    uint32_t max_tile_side_;
    uint32_t tile_side_;
    ProgressiveOptions options_;
    std::vector<uint32_t> divisors_;
    uint32_t pass_ = 0;
    std::vector<PixelRegion> tiles_;  // the current pass's, centre first
    size_t next_tile_ = 0;
    double ms_per_pixel_ = 0.0;
};

// The tiles covering a width x height image, the ones nearest the centre first
// (what the eye looks at), then by row and column.
std::vector<PixelRegion> tiles_centre_first(uint32_t width, uint32_t height, uint32_t tile_size);

}  // namespace lc::client
