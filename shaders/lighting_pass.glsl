// What the reference and lightcuts passes share: reading the G-buffer, the
// classic lights, and storing a pixel with its cut and the frame counters.
#ifndef LC_LIGHTING_PASS_GLSL
#define LC_LIGHTING_PASS_GLSL

#include "common_lighting.glsl"
#include "frame_bindings.glsl"
#include "loop_limits.glsl"
#include "shadow_rays.glsl"

struct SurfacePoint {
    vec3 position;
    vec3 normal;
    vec3 albedo;
    vec3 emissive;
};

// False for background pixels (no geometry).
bool load_surface(ivec2 pixel, out SurfacePoint p) {
    vec4 position = imageLoad(gbuffer_position, pixel);
    p.position = position.xyz;
    p.normal = imageLoad(gbuffer_normal, pixel).xyz;
    p.albedo = imageLoad(gbuffer_albedo, pixel).rgb;
    p.emissive = imageLoad(gbuffer_emissive, pixel).rgb;
    return position.w != 0.0;
}

vec3 classic_irradiance(SurfacePoint p) {
    vec3 e = vec3(0.0);
    if (kClassicLights) {
        uint i = 0u;
        for (; i + kLoopUnroll <= frame.classic_count; i += kLoopUnroll) {
            e += visible_irradiance(classic_lights[i], p.position, p.normal);
            e += visible_irradiance(classic_lights[i + 1u], p.position, p.normal);
            e += visible_irradiance(classic_lights[i + 2u], p.position, p.normal);
            e += visible_irradiance(classic_lights[i + 3u], p.position, p.normal);
        }
        for (; i < frame.classic_count; ++i)
            e += visible_irradiance(classic_lights[i], p.position, p.normal);
    }
    return e;
}

// L = f_r * sum(E) + emissive, with f_r = albedo / pi (Lambert).
vec3 outgoing_radiance(SurfacePoint p, vec3 irradiance) {
    vec3 radiance = p.albedo * (1.0 / kPi) * irradiance;
    if (kEmissive) radiance += p.emissive;
    return radiance;
}

void store_background(ivec2 pixel) {
    imageStore(hdr_image, pixel, vec4(0.0));
    imageStore(cut_image, pixel, uvec4(0u));
}

// This invocation's shadow rays, and whether the device's loop limit ended a
// walk of it (`cut_short`: the cut's walk; shadow rays note their own).
void flush_pixel_counters(bool cut_short) {
    flush_shadow_ray_count();
    if (cut_short || g_shadow_walk_cut_short) atomicAdd(counters.loop_limit_stops, 1u);
}

// Non-finite radiance is counted and written as 0, so no NaN/Inf reaches an image.
void store_pixel(ivec2 pixel, vec3 radiance, uint cut_size, uint cut_hash, bool cut_short) {
    flush_pixel_counters(cut_short);
    if (any(isnan(radiance)) || any(isinf(radiance))) {
        atomicAdd(counters.nonfinite_pixels, 1u);
        radiance = vec3(0.0);
    }
    imageStore(hdr_image, pixel, vec4(radiance, 1.0));
    imageStore(cut_image, pixel, uvec4(cut_size, cut_hash, 0u, 0u));
    atomicMax(counters.max_cut, cut_size);
    atomicAdd(counters.geometry_pixels, 1u);
}

#endif
