#pragma once
// The form factor from a differential area to a polygon, exact for a fully
// visible polygon (Lambert's contour integral; Baum, Rushmeier and Winget
// 1989, eq. 2). The radiosity solver multiplies it by a visibility fraction.
#include <glm/vec3.hpp>

namespace lc::bake {

// F(dA_x -> triangle): the fraction of the power leaving a Lambertian dA at
// `x` with unit normal `n` that reaches the triangle. Only the part of the
// triangle above the tangent plane at x counts.
double point_triangle_form_factor(glm::dvec3 x, glm::dvec3 n, const glm::dvec3 (&triangle)[3]);

}  // namespace lc::bake
