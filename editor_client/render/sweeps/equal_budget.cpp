#include "editor_client/render/sweeps/equal_budget.h"

#include <cmath>
#include <limits>

namespace lc::client {
namespace {

double interpolate(const CostErrorPoint& a, const CostErrorPoint& b, double budget) {
    if (b.cost <= a.cost) return b.error;
    if (a.cost <= 0.0 || a.error <= 0.0 || b.error <= 0.0) {
        const double t = (budget - a.cost) / (b.cost - a.cost);
        return a.error + t * (b.error - a.error);
    }
    const double t = std::log(budget / a.cost) / std::log(b.cost / a.cost);
    return std::exp(std::log(a.error) + t * std::log(b.error / a.error));
}

}  // namespace

double error_at_budget(std::span<const CostErrorPoint> points, double budget) {
    const double none = std::numeric_limits<double>::quiet_NaN();
    if (points.empty() || !(budget >= points.front().cost) || budget > points.back().cost) return none;
    for (size_t i = 1; i < points.size(); ++i) {
        if (budget <= points[i].cost) return interpolate(points[i - 1], points[i], budget);
    }
    return points.front().error;  // one point, and the budget is its cost
}

}  // namespace lc::client
