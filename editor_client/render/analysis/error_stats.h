#pragma once
// Lightcuts against the reference, per pixel and summarised, and the images
// derived from HDR read-backs on the CPU: the error heatmap and auto exposure.
//
// Relative error of a pixel: |Y(lightcuts) - Y(reference)| / Y(reference),
// Y = Rec. 709 luminance of the linear radiance. It is measured only where the
// reference is non-negligible: geometry pixels whose reference luminance
// exceeds kNegligibleFraction x the mean reference luminance over geometry
// (darker pixels are black on screen and their ratio means nothing).
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/result.h"

namespace lc::client {

inline constexpr double kNegligibleFraction = 1e-3;
// Rows at the bottom of an error heatmap given to the colour scale bar.
inline constexpr uint32_t kErrorScaleBarRows = 16;

struct ErrorStats {
    double rel_err_mean = 0.0;
    double rel_err_p99 = 0.0;      // 99th percentile (nearest rank)
    double frac_over_error = 0.0;  // fraction of measured pixels with rel_err > error_ratio
    double max_err = 0.0;
    uint64_t measured_pixels = 0;
    std::vector<float> per_pixel;  // relative error, -1 where not measured
};

// Both images RGBA float (alpha 0 on background), same size.
Result<ErrorStats> compute_error_stats(std::span<const float> lightcuts,
                                       std::span<const float> reference, uint32_t width,
                                       uint32_t height, double error_ratio);

// Fraction of the measured pixels whose relative error exceeds `threshold`
// (frac_over_error for another ratio, without measuring again).
double fraction_over(const ErrorStats& stats, double threshold);

// RGBA8 heatmap of ErrorStats::per_pixel: 0 dark blue .. 2 x error_ratio and
// above red, unmeasured geometry grey, background black, with the colour
// scale bar (0 left, 2 x error_ratio right) in the bottom rows.
std::vector<uint8_t> error_heatmap(const ErrorStats& stats, std::span<const float> reference,
                                   uint32_t width, uint32_t height, double error_ratio);

// Exposure that maps the log-average luminance of the lit geometry pixels
// (luminance above kLitFraction x the brightest) to 0.18, Reinhard's key
// value; 1 when there is no lit geometry.
inline constexpr double kLitFraction = 1e-4;
float auto_exposure(std::span<const float> hdr);

// RGBA8 display values of an RGBA float image (tone_mapping.h).
std::vector<uint8_t> tone_map_image(std::span<const float> hdr, float exposure);

}  // namespace lc::client
