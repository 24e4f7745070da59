#include "editor_client/editor/progressive_refinement.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "editor_client/editor/adaptive_resolution.h"

namespace lc::client {

uint64_t TileBatch::pixels() const {
    uint64_t sum = 0;
    for (const PixelRegion& tile : tiles) sum += tile.pixels();
    return sum;
}

std::vector<PixelRegion> tiles_centre_first(uint32_t width, uint32_t height, uint32_t tile_size) {
    std::vector<PixelRegion> tiles;
    for (uint32_t y = 0; y < height; y += tile_size)
        for (uint32_t x = 0; x < width; x += tile_size)
            tiles.push_back({x, y, std::min(tile_size, width - x), std::min(tile_size, height - y)});
    // Twice the distance, in whole pixels: exact, so the order is the same everywhere.
    auto distance2 = [&](const PixelRegion& t) {
        const int64_t dx = int64_t(2 * t.x + t.width) - int64_t(width);
        const int64_t dy = int64_t(2 * t.y + t.height) - int64_t(height);
        return dx * dx + dy * dy;
    };
    std::stable_sort(tiles.begin(), tiles.end(), [&](const PixelRegion& a, const PixelRegion& b) {
        return distance2(a) < distance2(b);
    });
    return tiles;
}

ProgressiveRefinement::ProgressiveRefinement(uint32_t width, uint32_t height, uint32_t alignment,
                                             ProgressiveOptions options)
    : width_(std::max(width, 1u)), height_(std::max(height, 1u)), options_(options) {
    alignment_ = std::max(alignment, 1u);
    max_tile_side_ = std::max((options_.tile_size + alignment_ - 1) / alignment_, 1u) * alignment_;
    tile_side_ = max_tile_side_;
    options_.max_tiles_per_frame = std::max(options_.max_tiles_per_frame, 1u);
    restart(1);
}

void ProgressiveRefinement::restart(uint32_t coarse_divisor) {
    divisors_.clear();
    if (coarse_divisor > 1) divisors_.push_back(coarse_divisor);
    divisors_.push_back(1);
    pass_ = 0;
    start_pass();
}

void ProgressiveRefinement::start_pass() {
    next_tile_ = 0;
    tiles_.clear();
    if (complete()) return;
    // The largest tile within the budget, by what the last passes cost.
    tile_side_ = max_tile_side_;
    while (tile_side_ > alignment_ && ms_per_pixel_ * tile_side_ * tile_side_ > options_.frame_budget_ms)
        tile_side_ -= alignment_;
    const uint32_t divisor = divisors_[pass_];
    tiles_ = tiles_centre_first(reduced_size(width_, divisor), reduced_size(height_, divisor),
                                tile_side_);
}

uint32_t ProgressiveRefinement::tiles_per_frame() const {
    if (ms_per_pixel_ <= 0.0) return 1;  // nothing learned yet: one tile
    const double tile_ms = ms_per_pixel_ * double(tile_side_) * double(tile_side_);
    const double fit = std::floor(options_.frame_budget_ms / tile_ms);
    return uint32_t(std::clamp(fit, 1.0, double(options_.max_tiles_per_frame)));
}

std::optional<TileBatch> ProgressiveRefinement::next_batch() {
    if (complete()) return std::nullopt;
    TileBatch batch;
    batch.pass = pass_;
    batch.divisor = divisors_[pass_];
    batch.width = reduced_size(width_, batch.divisor);
    batch.height = reduced_size(height_, batch.divisor);
    batch.new_image = next_tile_ == 0;
    const size_t count = std::min<size_t>(tiles_per_frame(), tiles_.size() - next_tile_);
    batch.tiles.assign(tiles_.begin() + ptrdiff_t(next_tile_),
                       tiles_.begin() + ptrdiff_t(next_tile_ + count));
    next_tile_ += count;
    if (next_tile_ == tiles_.size()) {
        ++pass_;
        start_pass();
    }
    return batch;
}

void ProgressiveRefinement::report(const TileBatch& batch, double gpu_ms) {
    const uint64_t pixels = batch.pixels();
    if (pixels == 0 || !std::isfinite(gpu_ms) || gpu_ms < 0.0) return;
    const double measured = gpu_ms / double(pixels);
    // Smoothed: tiles in the middle of a view cost more than those at its edge.
    ms_per_pixel_ = ms_per_pixel_ <= 0.0 ? measured : 0.6 * ms_per_pixel_ + 0.4 * measured;
}

double ProgressiveRefinement::percent() const {
    if (complete() || tiles_.empty()) return 100.0;
    return 100.0 * double(next_tile_) / double(tiles_.size());
}

}  // namespace lc::client
