// The shading model, written once: the shaders include it as GLSL (float),
// lightcuts/shading_model.h as C++ (double) in lc::shading.
//
// Radiance leaving a surface point x with normal n towards the camera, from one
// light:  L = f_r * E,  E = I * color * G * V (V: shadow_ray.h; f_r: material.glsl.h).
//   point/spot:  G = window(d, range) * max(cos_theta, 0) / max(d^2, kMinDistance^2)
//                window(d, range) = clamp(1 - (d/range)^4, 0, 1)^2 (KHR_lights_punctual)
//                spot: G *= clamp((cos_s - cos_outer) / max(cos_inner - cos_outer, 1e-4), 0, 1)^2
//   oriented:    G as a point light (no spot factor) times the emitter's
//                cosine max(dot(d, n_e), 0), d the unit direction from the light
//                to x, n_e its normal (`direction`): a cosine emitter (the
//                paper's oriented light, a point of an area light)
//                A radiosity patch is an oriented light with a source radius
//                r = sqrt(area / pi): its inverse square is 1 / (d^2 + r^2),
//                the on-axis irradiance of a uniformly emitting disk, exact on
//                its axis and finite at d = 0, so a patch never spikes. Every
//                other light has r = 0. The cluster bounds' 1 / d_min^2 stays
//                above it (cluster_bounds.glsl.h).
//   directional: G = max(cos_theta, 0) (intensity in lux)
#ifndef LC_DEVICE_SHADING_GLSL_H
#define LC_DEVICE_SHADING_GLSL_H

#include "lightcuts/device/real_math.glsl.h"

#ifdef __cplusplus
namespace lc::shading {
using namespace lc::device;
#endif

LC_CONST real kPi = 3.14159265358979323846;
// Keeps the inverse-square law finite at a shading point that sits on a light.
LC_CONST real kMinDistance = 1e-3;
LC_CONST real kSpotMinCosDelta = 1e-4;

// range <= 0: no window.
LC_INLINE real range_window(real distance, real range) {
    if (range <= 0.0) return 1.0;
    real ratio = distance / range;
    real r2 = ratio * ratio;
    real w = clamp(1.0 - r2 * r2, 0.0, 1.0);
    return w * w;
}

LC_INLINE real inverse_square(real distance_squared) {
    return 1.0 / max(distance_squared, kMinDistance * kMinDistance);
}

// The spot's 1 / max(cos_inner - cos_outer, 1e-4), which the GPU light stores
// precomputed.
LC_INLINE real spot_scale(real cos_inner, real cos_outer) {
    return 1.0 / max(cos_inner - cos_outer, kSpotMinCosDelta);
}

// The oriented light's emission factor: its cosine to the light's normal,
// `from_light` the unit direction from the light to the shaded point.
LC_INLINE real emitter_cosine(real3 from_light, real3 normal) {
    return max(dot(from_light, normal), 0.0);
}

LC_INLINE real spot_attenuation(real cos_spot, real cos_outer, real scale) {
    real a = clamp((cos_spot - cos_outer) * scale, 0.0, 1.0);
    return a * a;
}

// A light, or a cluster through its representative, as G sees it.
struct Emitter {
    bool directional;
    bool spot;
    bool oriented;
    real3 position;
    real3 direction;   // where the light travels; the emitting normal when oriented
    real range;        // <= 0: no window
    real cos_outer;    // spot only, like spot_scale
    real spot_scale;
    real source_radius;  // a radiosity patch's disk radius; 0 for every other light
};

// G of the emitter at x with unit normal n. `l` gets the unit direction
// towards the light, for the material; on a positional light itself there is
// none (l = 0) and G is 0.
LC_INLINE real light_geometry(LC_IN(Emitter) e, real3 x, real3 n, LC_OUT(real3) l) {
    if (e.directional) {
        // Stored directions are unit to float precision only; a sharp lobe notices.
        real len = length(e.direction);
        l = len > 0.0 ? -e.direction / len : real3(0.0);
        return max(dot(n, -e.direction), 0.0);
    }
    real3 to_light = e.position - x;
    real d2 = dot(to_light, to_light);
    l = real3(0.0);
    if (!(d2 > 0.0)) return 0.0;
    real d = sqrt(d2);
    l = to_light / d;
    real cos_theta = dot(n, to_light) / d;
    if (!(cos_theta > 0.0)) return 0.0;
    real g = range_window(d, e.range) * cos_theta * inverse_square(d2 + e.source_radius * e.source_radius);
    if (e.spot) g *= spot_attenuation(dot(-to_light / d, e.direction), e.cos_outer, e.spot_scale);
    if (e.oriented) g *= emitter_cosine(-to_light / d, e.direction);
    return g;
}

#ifdef __cplusplus
}  // namespace lc::shading
#endif

#endif
