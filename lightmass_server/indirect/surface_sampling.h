#pragma once
// Sampling on surfaces and hemispheres, shared by the photon tracer, the
// radiosity solver's visibility and the tests' path-traced reference.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "lightcuts/material_model.h"
#include "lightcuts/scene_geometry.h"

namespace lc::bake {

// Two unit tangents completing `n` to a right-handed frame (Duff et al. 2017).
struct TangentFrame {
    glm::vec3 t;
    glm::vec3 b;
    glm::vec3 n;
};

inline TangentFrame tangent_frame(glm::vec3 n) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    return {{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
}

inline glm::vec3 to_world(const TangentFrame& f, glm::vec3 local) {
    return local.x * f.t + local.y * f.b + local.z * f.n;
}

// Cosine-weighted direction about +z from two uniforms (Malley's method):
// pdf = cos(theta) / pi, which cancels a Lambertian surface's cosine.
inline glm::vec3 cosine_hemisphere(double u1, double u2) {
    double r = std::sqrt(u1);
    double phi = 2.0 * std::numbers::pi * u2;
    double z = std::sqrt(std::max(0.0, 1.0 - u1));
    return glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

// Uniform direction on the unit sphere: pdf = 1 / (4 pi).
inline glm::vec3 uniform_sphere(double u1, double u2) {
    double z = 1.0 - 2.0 * u1;
    double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    double phi = 2.0 * std::numbers::pi * u2;
    return glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

// Uniform direction in the cone of half-angle acos(cos_max) about +z:
// pdf = 1 / (2 pi (1 - cos_max)).
inline glm::vec3 uniform_cone(double u1, double u2, double cos_max) {
    double z = 1.0 - u1 * (1.0 - cos_max);
    double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    double phi = 2.0 * std::numbers::pi * u2;
    return glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

// Uniform point on a triangle (the square-root parametrisation).
inline glm::vec3 uniform_triangle_point(const glm::vec3 (&p)[3], double u1, double u2) {
    double s = std::sqrt(u1);
    float b0 = float(1.0 - s);
    float b1 = float(u2 * s);
    return b0 * p[0] + b1 * p[1] + (1.0f - b0 - b1) * p[2];
}

// The side a triangle reflects and emits from: its winding normal, turned
// to agree with the vertex normals the scene gave. Float for the bounces;
// double for the area-light samples (emitters/area_light_sampler), whose tree
// bytes depend on it.
template <typename Real = float>
glm::vec<3, Real> front_normal(const SurfaceTriangle& t) {
    using Vec = glm::vec<3, Real>;
    Vec n = glm::normalize(Vec(triangle_cross(t)));
    Vec shading = Vec(t.normals[0]) + Vec(t.normals[1]) + Vec(t.normals[2]);
    return glm::dot(n, shading) < Real(0) ? -n : n;
}

// The albedo a bounce reflects: the renderer's material under diffuse light
// (shading::bounce_albedo), so the bake and the shading agree on energy.
inline glm::vec3 bounce_albedo(const SurfaceMaterial& m) {
    return glm::vec3(shading::bounce_albedo(glm::dvec3(m.base_color), double(m.metallic), double(m.roughness)));
}

// Offset that keeps a ray leaving a surface from hitting it again, scaled to the scene.
inline float ray_epsilon(float scene_extent) { return 1e-4f * std::max(scene_extent, 1e-3f); }

}  // namespace lc::bake
