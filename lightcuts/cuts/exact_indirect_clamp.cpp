#include "lightcuts/cuts/exact_indirect_clamp.h"

#include <algorithm>
#include <functional>
#include <vector>

namespace lc {

double exact_clamp_threshold(double others, std::span<const double> lights, double ratio) {
    std::vector<double> sorted(lights.begin(), lights.end());
    std::sort(sorted.begin(), sorted.end(), std::greater<>());
    const size_t n = sorted.size();
    // below[k]: the sum of every light but the k largest, summed from the smallest.
    std::vector<double> below(n + 1, 0.0);
    for (size_t k = n; k-- > 0;) below[k] = below[k + 1] + sorted[k];
    // With the k largest above t and the rest under it, the equation is linear;
    // its root is the largest one when it lies on that piece. Pieces of fewer
    // lights above lie higher, so the first that holds its root is the answer.
    for (size_t k = 0; k <= n; ++k) {
        const double denominator = 1.0 - ratio * double(k);
        if (!(denominator > 0.0)) break;
        const double t = ratio * (others + below[k]) / denominator;
        const bool under_the_kth = k == 0 || t <= sorted[k - 1];
        const bool over_the_rest = k == n || t >= sorted[k];
        if (under_the_kth && over_the_rest) return t;
    }
    // Only with nothing but the lights: as many comparable lights as 1 / ratio or fewer.
    return 0.0;
}

ExactClamp exact_indirect_clamp(const glm::dvec3& others, std::span<const glm::dvec3> lights, double ratio) {
    ExactClamp result;
    std::vector<double> channel(lights.size());
    for (int c = 0; c < 3; ++c) {
        for (size_t i = 0; i < lights.size(); ++i) channel[i] = lights[i][c];
        const double t = exact_clamp_threshold(others[c], channel, ratio);
        double kept = 0.0, removed = 0.0;
        for (double l : channel) {
            kept += std::min(l, t);
            removed += std::max(l - t, 0.0);
        }
        result.threshold[c] = t;
        result.removed[c] = removed;
        result.radiance[c] = others[c] + kept;
    }
    return result;
}

}  // namespace lc
