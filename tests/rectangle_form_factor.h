#pragma once
// Closed-form irradiance under a Lambertian square emitter (SPEC.md §11), for
// the area-light tests on the CPU and on the GPU.
#include <cmath>
#include <numbers>

namespace lc::test {

// The form factor from a point to a rectangle with one corner straight above
// it: extents a and b along the edges, c below.
inline double corner_form_factor(double a, double b, double c) {
    const double X = a / c, Y = b / c;
    const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * std::numbers::pi);
}

// E at (x, z) on a plane `c` below the square [-h, h]^2 of radiance L facing
// it: four corner rectangles, subtracted where the point lies outside.
inline double square_irradiance(double radiance, double h, double c, double x, double z) {
    double f = 0.0;
    for (double sx : {-1.0, 1.0})
        for (double sz : {-1.0, 1.0}) {
            const double a = sx * h - x, b = sz * h - z;
            f += (a * sx >= 0 ? 1 : -1) * (b * sz >= 0 ? 1 : -1) * corner_form_factor(std::abs(a), std::abs(b), c);
        }
    return std::numbers::pi * radiance * f;
}

}  // namespace lc::test
