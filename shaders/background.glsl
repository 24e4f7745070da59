// What a pixel without geometry shows: the environment along its eye ray
// (the map with its intensity and rotation, or the sun and sky), or black
// without one. Every lighting pass stores it the same way, with alpha 0 so
// that exposure and error statistics still see geometry only.
#ifndef LC_BACKGROUND_GLSL
#define LC_BACKGROUND_GLSL

#include "frame_bindings.glsl"
#include "lightcuts/device/equirect_map.glsl.h"
#include "lightcuts/device/preetham_sky.glsl.h"

vec3 eye_ray_direction(ivec2 pixel) {
    vec2 centre = vec2(pixel) + vec2(0.5);
    return normalize(background.ray_at_origin + centre.x * background.ray_step_x +
                     centre.y * background.ray_step_y);
}

// The nearest texel, as lightcuts/equirect_map.h's equirect_radiance.
vec3 map_radiance(vec3 d) {
    uint x = min(uint(equirect_u(d, background.rotation) * float(background.map_width)),
                 background.map_width - 1u);
    uint y = min(uint(equirect_v(d) * float(background.map_height)), background.map_height - 1u);
    return environment_texels[y * background.map_width + x].radiance;
}

vec3 sky_radiance(vec3 d) {
    vec3 radiance = preetham_sky_radiance(d, background.sun_direction, background.turbidity);
    if (dot(d, background.sun_direction) >= background.sun_cos_radius) radiance += background.sun_radiance;
    return radiance;
}

vec3 background_radiance(ivec2 pixel) {
    if (background.kind == kBackgroundBlack) return vec3(0.0);
    vec3 d = eye_ray_direction(pixel);
    vec3 radiance = background.kind == kBackgroundMap ? map_radiance(d) : sky_radiance(d);
    return background.intensity * radiance;
}

#endif
