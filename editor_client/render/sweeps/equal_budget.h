#pragma once
// "Error at equal time" and "at equal rays": what a variant's error is after
// spending a budget (GPU ms, or shadow rays per pixel) on a still view, read
// off its measured points (cost after N frames, error after N frames).
#include <cstdint>
#include <span>

namespace lc::client {

struct CostErrorPoint {
    double cost = 0.0;   // cumulative: total GPU ms or shadow rays per pixel after the frames
    double error = 0.0;  // measured after those frames
};

// The error at `budget`, interpolated linearly in log(cost) and log(error)
// between the two measured points around it (an unbiased estimator's error
// falls as a power of its frames, a straight line there; linear in error
// where one of them is 0). NaN outside the measured costs: a budget below
// the first point buys not even the first frame's count, one past the last
// would be a guess. `points` ascend in cost.
double error_at_budget(std::span<const CostErrorPoint> points, double budget);

}  // namespace lc::client
