// The material model, written once: the shaders include it as GLSL (float),
// lightcuts/material_model.h as C++ (double) in lc::shading.
//
// glTF's metallic-roughness parameters as a Lambert term plus one glossy lobe
// that is symmetric about the mirror direction, so that the paper's cosine
// bounds (Sec. 4.1: "any similar BRDF component that is symmetric about an
// axis") bound it over a cluster's box (cluster_bounds.glsl.h).
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
// (n = 0) it is the constant 1/pi, Lambert: a rough material folds its
// specular into the diffuse term and shades exactly as a Lambert surface of
// albedo diffuse + F0 (a white rough dielectric keeps albedo 1). Fresnel's
// angle dependence is left out, so the bound stays a product of
// one-dimensional maxima.
#ifndef LC_DEVICE_MATERIAL_GLSL_H
#define LC_DEVICE_MATERIAL_GLSL_H

#include "lightcuts/device/shading.glsl.h"

#ifdef __cplusplus
namespace lc::shading {
using namespace lc::device;
#endif

LC_CONST real kDielectricF0 = 0.04;
// Smoother surfaces render as this roughness (n ~ 4e4: a lobe ~0.6 degrees
// wide), so the lobe stays finite and representable in float.
LC_CONST real kMinRoughness = 0.1;

LC_INLINE real lobe_exponent(real roughness) {
    real r = clamp(roughness, kMinRoughness, 1.0);
    real alpha2 = r * r * r * r;
    return max(4.0 / alpha2 - 4.0, 0.0);
}

// The lobe at cosine c to the mirror direction; increasing in c, so its bound
// over a box is the lobe at the box's largest cosine. pow is only called on a
// positive base.
LC_INLINE real glossy_lobe(real cos_to_mirror, real exponent) {
    real h = clamp((1.0 + cos_to_mirror) * 0.5, 0.0, 1.0);
    real n = exponent;
    real peak = (n + 1.0) * (n + 2.0) / (4.0 * kPi * (n + exp2(-(n + 1.0))));
    if (!(h > 0.0)) return exponent > 0.0 ? 0.0 : peak;
    return peak * pow(h, exponent);
}

// Whether a lobe contributes anything: n > 0 (n = 0 folds into the diffuse
// term) and some F0 above 0 (a black metal reflects nothing).
LC_INLINE bool has_lobe(real3 specular, real exponent) {
    return exponent > 0.0 && (specular.x > 0.0 || specular.y > 0.0 || specular.z > 0.0);
}

struct SurfaceMaterial {
    real3 diffuse;   // linear diffuse albedo
    real3 specular;  // F0 of the lobe; 0 when folded into diffuse
    real exponent;   // n of the lobe
};

LC_INLINE SurfaceMaterial surface_material(real3 base_color, real metallic, real roughness) {
    real m = clamp(metallic, 0.0, 1.0);
    SurfaceMaterial s;
    s.diffuse = (1.0 - m) * (1.0 - kDielectricF0) * base_color;
    real3 f0 = kDielectricF0 * (1.0 - m) + m * base_color;
    s.exponent = lobe_exponent(roughness);
    s.specular = real3(0.0);
    if (s.exponent > 0.0) {
        s.specular = f0;
    } else {
        s.diffuse += f0;  // the lobe is the constant 1/pi: Lambert
    }
    return s;
}

// The share of light the lobe reflects under uniform illumination, averaged
// over the directions it leaves in (cosine-weighted): 1 at n = 0 (Lambert),
// falling to 2/3 as the lobe narrows (a narrow lobe reflects cos(theta) of the
// light arriving at angle theta, and the cosine-weighted mean of cos is 2/3).
// A rational fit to the double integral of lobe x cos x cos, within 0.07% of
// it at every n (material_model_test integrates it).
LC_INLINE real lobe_hemispherical_albedo(real exponent) {
    real n = max(exponent, 0.0);
    real beyond_mean = (1.0 + 0.01504 * n) / (1.0 + 0.5842 * n + 0.10863 * n * n);
    return (2.0 + beyond_mean) / 3.0;
}

// The albedo a Lambertian bounce of the bake reflects: the energy this model
// reflects under diffuse light, so the server's VPLs and radiosity patches
// carry what the shader integrates. At roughness 1: 0.96 (1 - metallic) base
// + mix(0.04, base, metallic).
LC_INLINE real3 bounce_albedo(real3 base_color, real metallic, real roughness) {
    SurfaceMaterial s = surface_material(base_color, metallic, roughness);
    real3 glossy = s.specular * lobe_hemispherical_albedo(s.exponent);
    return clamp(s.diffuse + glossy, real3(0.0), real3(1.0));
}

// Direction of perfect reflection of the view: the lobe's axis. The eye sits
// on the normal's side (the G-buffer flips normals towards the camera).
LC_INLINE real3 mirror_direction(real3 normal, real3 position, real3 eye) {
    real3 to_eye = eye - position;
    real len = length(to_eye);
    if (!(len > 0.0)) return normal;
    real3 v = to_eye / len;
    return 2.0 * dot(normal, v) * normal - v;
}

LC_INLINE real3 diffuse_brdf(real3 albedo) { return albedo / kPi; }

// f_r towards the unit direction l.
LC_INLINE real3 brdf(real3 albedo, real3 specular, real exponent, real3 mirror, real3 l) {
    if (!has_lobe(specular, exponent)) return diffuse_brdf(albedo);
    return diffuse_brdf(albedo) + specular * glossy_lobe(dot(mirror, l), exponent);
}

#ifdef __cplusplus
}  // namespace lc::shading
#endif

#endif
