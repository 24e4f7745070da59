#include "editor_client/render/analysis/error_stats.h"

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "lightcuts/tone_mapping.h"

namespace lc::client {
namespace {

double luminance(std::span<const float> rgba, size_t pixel) {
    const float* p = rgba.data() + pixel * 4;
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

bool is_geometry(std::span<const float> rgba, size_t pixel) { return rgba[pixel * 4 + 3] != 0.0f; }

// Dark blue -> blue -> green -> yellow -> red for t in [0, 1] (as cut_view.comp).
glm::vec3 heat_colour(float t) {
    static const glm::vec3 stops[5] = {{0.05f, 0.03f, 0.35f}, {0.0f, 0.45f, 1.0f},
                                       {0.1f, 0.85f, 0.35f},  {1.0f, 0.9f, 0.0f},
                                       {0.95f, 0.1f, 0.05f}};
    float x = std::clamp(t, 0.0f, 1.0f) * 4.0f;
    int i = std::min(int(x), 3);
    return glm::mix(stops[i], stops[i + 1], x - float(i));
}

void put(std::vector<uint8_t>& out, size_t pixel, const glm::vec3& colour) {
    for (int c = 0; c < 3; ++c)
        out[pixel * 4 + c] = uint8_t(std::lround(std::clamp(colour[c], 0.0f, 1.0f) * 255.0f));
    out[pixel * 4 + 3] = 255;
}

}  // namespace

Result<ErrorStats> compute_error_stats(std::span<const float> lightcuts,
                                       std::span<const float> reference, uint32_t width,
                                       uint32_t height, double error_ratio) {
    const size_t pixels = size_t(width) * height;
    if (lightcuts.size() != pixels * 4 || reference.size() != pixels * 4)
        return make_error("error stats: images of " + std::to_string(lightcuts.size()) + " and " +
                          std::to_string(reference.size()) + " floats do not match " +
                          std::to_string(width) + "x" + std::to_string(height) + " RGBA");
    double mean = 0.0;
    uint64_t geometry = 0;
    for (size_t i = 0; i < pixels; ++i) {
        const double y = luminance(reference, i);
        if (!is_geometry(reference, i) || !std::isfinite(y)) continue;
        mean += y;
        ++geometry;
    }
    mean = geometry > 0 ? mean / double(geometry) : 0.0;
    const double threshold = kNegligibleFraction * mean;

    ErrorStats stats;
    stats.per_pixel.assign(pixels, -1.0f);
    std::vector<double> errors;
    double sum = 0.0;
    uint64_t over = 0;
    for (size_t i = 0; i < pixels; ++i) {
        const double y_ref = luminance(reference, i);
        if (!is_geometry(reference, i) || !(y_ref > threshold) || !std::isfinite(y_ref)) continue;
        const double y = luminance(lightcuts, i);
        // A non-finite lightcuts value is the worst error there is; keep it finite.
        const double e = std::isfinite(y) ? std::abs(y - y_ref) / y_ref : 1e30;
        stats.per_pixel[i] = float(std::min(e, 1e30));
        errors.push_back(e);
        sum += e;
        if (e > error_ratio) ++over;
        stats.max_err = std::max(stats.max_err, e);
    }
    stats.measured_pixels = errors.size();
    if (!errors.empty()) {
        stats.rel_err_mean = sum / double(errors.size());
        stats.frac_over_error = double(over) / double(errors.size());
        // Nearest rank: the smallest value with at least 99% of the values <= it.
        size_t rank = size_t(std::ceil(0.99 * double(errors.size())));
        rank = std::clamp<size_t>(rank, 1, errors.size()) - 1;
        std::nth_element(errors.begin(), errors.begin() + ptrdiff_t(rank), errors.end());
        stats.rel_err_p99 = errors[rank];
    }
    return stats;
}

double fraction_over(const ErrorStats& stats, double threshold) {
    if (stats.measured_pixels == 0) return 0.0;
    uint64_t over = 0;
    for (float e : stats.per_pixel) over += e >= 0.0f && double(e) > threshold;
    return double(over) / double(stats.measured_pixels);
}

std::vector<uint8_t> error_heatmap(const ErrorStats& stats, std::span<const float> reference,
                                   uint32_t width, uint32_t height, double error_ratio) {
    std::vector<uint8_t> out(size_t(width) * height * 4, 0);
    const double scale_top = error_ratio > 0.0 ? 2.0 * error_ratio : 1.0;
    const uint32_t bar_rows = std::min(kErrorScaleBarRows, height / 4);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t(y) * width + x;
            glm::vec3 colour(0.0f);
            if (y + bar_rows >= height && bar_rows > 0) {
                // The scale bar under a one-pixel black separator.
                const bool separator = y + bar_rows == height;
                const float t = width > 1 ? float(x) / float(width - 1) : 0.0f;
                colour = separator ? glm::vec3(0.0f) : heat_colour(t);
            } else if (i < stats.per_pixel.size() && stats.per_pixel[i] >= 0.0f) {
                colour = heat_colour(float(double(stats.per_pixel[i]) / scale_top));
            } else if (i * 4 + 3 < reference.size() && reference[i * 4 + 3] != 0.0f) {
                colour = glm::vec3(0.2f);  // geometry with a negligible reference
            }
            put(out, i, colour);
        }
    }
    return out;
}

float auto_exposure(std::span<const float> hdr) {
    // Lit pixels only: a black ceiling above downward lights, or a shadow,
    // would otherwise drag the log-average towards log(0) and wash out the
    // rest of the image.
    double brightest = 0.0;
    for (size_t i = 0; i * 4 + 3 < hdr.size(); ++i) {
        if (!is_geometry(hdr, i)) continue;
        const double y = luminance(hdr, i);
        if (std::isfinite(y)) brightest = std::max(brightest, y);
    }
    const double lit = kLitFraction * brightest;
    // Deterministic: a fixed-order sum in double.
    double log_sum = 0.0;
    uint64_t count = 0;
    for (size_t i = 0; i * 4 + 3 < hdr.size(); ++i) {
        if (!is_geometry(hdr, i)) continue;
        const double y = luminance(hdr, i);
        if (!std::isfinite(y) || !(y > lit)) continue;
        log_sum += std::log(y);
        ++count;
    }
    if (count == 0) return 1.0f;
    const double log_average = std::exp(log_sum / double(count));
    const double exposure = 0.18 / log_average;
    if (!std::isfinite(exposure) || !(exposure > 0.0)) return 1.0f;
    return float(std::min(exposure, 1e12));
}

std::vector<uint8_t> tone_map_image(std::span<const float> hdr, float exposure) {
    std::vector<uint8_t> out(hdr.size(), 0);
    for (size_t i = 0; i + 3 < hdr.size(); i += 4) {
        for (int c = 0; c < 3; ++c) out[i + c] = tone::to_display_byte(hdr[i + c], exposure);
        out[i + 3] = 255;
    }
    return out;
}

}  // namespace lc::client
