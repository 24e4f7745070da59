#include "lightmass_server/indirect/point_polygon_form_factor.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

namespace lc::bake {
namespace {

// A triangle clipped by a plane has at most four vertices.
struct Polygon {
    glm::dvec3 v[4];
    int count = 0;
};

// Sutherland-Hodgman against the half-space dot(n, p - x) >= 0.
Polygon clip_above(const glm::dvec3 (&triangle)[3], glm::dvec3 x, glm::dvec3 n) {
    Polygon out;
    for (int i = 0; i < 3; ++i) {
        glm::dvec3 a = triangle[i];
        glm::dvec3 b = triangle[(i + 1) % 3];
        double da = glm::dot(n, a - x);
        double db = glm::dot(n, b - x);
        if (da >= 0.0) out.v[out.count++] = a;
        if ((da >= 0.0) != (db >= 0.0)) out.v[out.count++] = a + (b - a) * (da / (da - db));
    }
    return out;
}

}  // namespace

double point_triangle_form_factor(glm::dvec3 x, glm::dvec3 n, const glm::dvec3 (&triangle)[3]) {
    Polygon p = clip_above(triangle, x, n);
    if (p.count < 3) return 0.0;
    // F = (1 / 2 pi) sum over edges of gamma_e (n . unit(R_e x R_e+1)).
    double sum = 0.0;
    for (int i = 0; i < p.count; ++i) {
        glm::dvec3 r0 = p.v[i] - x;
        glm::dvec3 r1 = p.v[(i + 1) % p.count] - x;
        glm::dvec3 c = glm::cross(r0, r1);
        double c_length = glm::length(c);
        double l0 = glm::length(r0);
        double l1 = glm::length(r1);
        if (!(c_length > 0.0) || !(l0 > 0.0) || !(l1 > 0.0)) continue;
        double gamma = std::atan2(c_length, glm::dot(r0, r1));
        sum += gamma * glm::dot(n, c) / c_length;
    }
    double f = std::abs(sum) / (2.0 * std::numbers::pi);
    return std::isfinite(f) ? std::min(f, 1.0) : 0.0;
}

}  // namespace lc::bake
