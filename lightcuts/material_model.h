#pragma once
// Our material: glTF's metallic-roughness parameters as a Lambert term plus one
// glossy lobe that is symmetric about the mirror direction, so that the
// paper's cosine bounds (Sec. 4.1: "any similar BRDF component that is
// symmetric about an axis") bound it over a cluster's box. Mirrored in
// shaders/material_model.glsl; tests compare the two.
//
//   f_r(l)   = diffuse / pi + specular * lobe(dot(mirror, l))
//   lobe(c)  = N(n) * ((1 + c) / 2)^n,  N(n) = (n + 1)(n + 2) / (4 pi (n + 2^-(n+1)))
//   diffuse  = (1 - metallic) * (1 - 0.04) * base_color
//   specular = mix(0.04, base_color, metallic)             (F0, at every angle)
//   n        = 4 / alpha^2 - 4,  alpha = roughness^2,  roughness in [0.1, 1]
//
// ((1 + c) / 2)^n = cos^(2n)(angle / 2), close to cos^(n/2)(angle) near the
// mirror direction: Phong with exponent n/2 = 2/alpha^2 - 2 (Walter et al.
// 2007's match to a microfacet width alpha). N(n) makes the lobe reflect
// exactly all the light arriving along the normal (its integral times cos over
// the hemisphere is 1 when the mirror direction is the normal), and less at
// other angles. Unlike max(c, 0)^m it needs no clamp, and at roughness 1
// (n = 0) it is the constant 1/pi, Lambert: a rough material folds its specular into the diffuse term and
// shades exactly as a Lambert surface of albedo diffuse + F0 (a white rough
// dielectric keeps albedo 1). Fresnel's angle dependence is left out, so the
// bound stays a product of one-dimensional maxima.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lc::shading {

inline constexpr double kDielectricF0 = 0.04;
// Smoother surfaces render as this roughness (n ~ 4e4: a lobe ~0.6 degrees wide),
// so the lobe stays finite and representable in float.
inline constexpr double kMinRoughness = 0.1;

template <typename T>
T lobe_exponent(T roughness) {
    const T r = std::clamp(roughness, T(kMinRoughness), T(1));
    const T alpha2 = r * r * r * r;
    return std::max(T(4) / alpha2 - T(4), T(0));
}

// The lobe at cosine c to the mirror direction; increasing in c, so its bound
// over a box is the lobe at the box's largest cosine.
template <typename T>
T glossy_lobe(T cos_to_mirror, T exponent) {
    const T h = std::clamp((T(1) + cos_to_mirror) * T(0.5), T(0), T(1));
    const T n = exponent;
    const T peak =
        (n + T(1)) * (n + T(2)) / (T(4) * T(std::numbers::pi) * (n + std::exp2(-(n + T(1)))));
    if (!(h > T(0))) return exponent > T(0) ? T(0) : peak;
    return peak * std::pow(h, exponent);
}

// Whether a lobe contributes anything: n > 0 (n = 0 folds into the diffuse
// term) and some F0 above 0 (a black metal reflects nothing).
inline bool has_lobe(const glm::dvec3& specular, double exponent) {
    return exponent > 0.0 && (specular.x > 0.0 || specular.y > 0.0 || specular.z > 0.0);
}

struct SurfaceMaterial {
    glm::dvec3 diffuse{1.0};   // linear diffuse albedo
    glm::dvec3 specular{0.0};  // F0 of the lobe; 0 when folded into diffuse
    double exponent = 0.0;     // n of the lobe
};

inline SurfaceMaterial surface_material(const glm::dvec3& base_color, double metallic,
                                        double roughness) {
    const double m = std::clamp(metallic, 0.0, 1.0);
    SurfaceMaterial out;
    out.diffuse = (1.0 - m) * (1.0 - kDielectricF0) * base_color;
    const glm::dvec3 f0 = kDielectricF0 * (1.0 - m) + m * base_color;
    out.exponent = lobe_exponent(roughness);
    if (out.exponent > 0.0) {
        out.specular = f0;
    } else {
        out.diffuse += f0;  // the lobe is the constant 1/pi: Lambert
    }
    return out;
}

// Direction of perfect reflection of the view: the lobe's axis. The eye sits
// on the normal's side (the G-buffer flips normals towards the camera).
inline glm::dvec3 mirror_direction(const glm::dvec3& normal, const glm::dvec3& position,
                                   const glm::dvec3& eye) {
    const glm::dvec3 to_eye = eye - position;
    const double len = glm::length(to_eye);
    if (!(len > 0.0)) return normal;
    const glm::dvec3 v = to_eye / len;
    return 2.0 * glm::dot(normal, v) * normal - v;
}

}  // namespace lc::shading
