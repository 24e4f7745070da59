// The segment a shadow ray tests, written once: the shaders include it as
// GLSL (shaders/shadow_rays.glsl, float), lightcuts/occlusion/shadow_ray.cpp as C++
// (double) in lc::shading.
//
// The ray leaves x `bias` along the unit normal n and `bias` further along
// its own direction l (towards the light), and ends `bias` short of a
// positional light (a light on a surface is not hidden by that surface).
// The step along l is what keeps creases lit: where a table leg meets the
// floor, the leg's G-buffer position may lie a rounding error below the
// floor; the normal's step is horizontal there and keeps it below, a ray
// towards a light above would meet the floor's underside at once. A step
// along the ray itself skips every surface closer than `bias` in that
// direction (a next-hit rule in the ray's origin), whichever way the
// normal points. x is a rounded position, so `bias` (shadow_ray_bias)
// holds enough ulps of the scene's largest coordinate.
#ifndef LC_DEVICE_SHADOW_SEGMENT_GLSL_H
#define LC_DEVICE_SHADOW_SEGMENT_GLSL_H

#include "lightcuts/device/real_math.glsl.h"

#ifdef __cplusplus
namespace lc::shading {
using namespace lc::device;
#endif

// origin + t direction, t in [0, t_max]; `traced` false: the light is too
// close to be hidden (within the offsets), count it visible.
struct ShadowSegment {
    real3 origin;
    real3 direction;
    real t_max;
    bool traced;
};

// A directional light shines along `light_direction`; a positional one
// sits at `light_position`. `far`: the end of a ray towards the former.
LC_INLINE ShadowSegment shadow_segment(real3 x, real3 n, bool directional, real3 light_position,
                                       real3 light_direction, real bias, real far) {
    ShadowSegment s;
    s.traced = true;
    s.t_max = far;
    real3 l = -light_direction;
    if (!directional) {
        real3 to_light = light_position - x;
        real d = length(to_light);
        // Within the two offsets of the light nothing can come between.
        if (!(d > 2.0 * bias)) {
            s.traced = false;
            d = max(d, bias);
        }
        l = to_light / d;
    }
    s.origin = x + (n + l) * bias;
    s.direction = l;
    if (!directional) {
        s.direction = light_position - s.origin;
        real distance = length(s.direction);
        s.t_max = 1.0 - bias / max(distance, bias);
    }
    return s;
}

#ifdef __cplusplus
}  // namespace lc::shading
#endif

#endif
