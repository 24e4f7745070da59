// What the reference and lightcuts passes share: reading the G-buffer, the
// classic lights, and storing a pixel with its cut and the frame counters, or
// the background (background.glsl) where no geometry was hit.
#ifndef LC_LIGHTING_PASS_GLSL
#define LC_LIGHTING_PASS_GLSL

#include "background.glsl"
#include "common_lighting.glsl"
#include "frame_bindings.glsl"
#include "indirect_clamp.glsl"
#include "material_model.glsl"
#include "shadow_rays.glsl"

// False for background pixels (no geometry). The G-buffer holds the base
// colour with metallic in albedo.w and roughness in normal.w.
bool load_surface(ivec2 pixel, out SurfacePoint p) {
    vec4 position = imageLoad(gbuffer_position, pixel);
    vec4 normal = imageLoad(gbuffer_normal, pixel);
    vec4 base = imageLoad(gbuffer_albedo, pixel);
    p.position = position.xyz;
    p.normal = normal.xyz;
    p.emissive = imageLoad(gbuffer_emissive, pixel).rgb;
    set_material(p, base.rgb, base.w, normal.w, frame.eye);
    return position.w != 0.0;
}

// f_r * I * color * G * V: what one light (or a cluster through its
// representative) adds to the radiance leaving p towards the camera.
vec3 light_radiance(GpuLight light, SurfacePoint p) {
    vec3 l;
    vec3 e = visible_irradiance(light, p.position, p.normal, l);
    return brdf_toward(p, l) * e;
}

// light_radiance, and what its shadow ray said (kSeen*, gpu_structs.h):
// reconstruction cuts reuse a sample's visibility between the samples.
vec3 light_radiance_seen(GpuLight light, SurfacePoint p, out uint seen) {
    vec3 l;
    vec3 e = light_irradiance(light, p.position, p.normal, l);
    bool lit = max(e.x, max(e.y, e.z)) > 0.0;
    float v = kShadows ? light_visibility(light, p.position, p.normal, lit) : 1.0;
    seen = !lit ? kSeenDark : (v > 0.0 ? kSeenVisible : kSeenBlocked);
    return brdf_toward(p, l) * (e * v);
}

vec3 classic_radiance(SurfacePoint p) {
    vec3 radiance = vec3(0.0);
    if (kClassicLights) {
        uint i = 0u;
        for (; i + kLoopUnroll <= frame.classic_count; i += kLoopUnroll) {
            radiance += light_radiance(classic_lights[i], p);
            radiance += light_radiance(classic_lights[i + 1u], p);
            radiance += light_radiance(classic_lights[i + 2u], p);
            radiance += light_radiance(classic_lights[i + 3u], p);
        }
        for (; i < frame.classic_count; ++i) radiance += light_radiance(classic_lights[i], p);
    }
    return radiance;
}

// What p adds besides the tree: its classic lights and its own emission.
vec3 classic_and_emitted_radiance(SurfacePoint p) {
    vec3 radiance = classic_radiance(p);
    if (kEmissive) radiance += p.emissive;
    return radiance;
}

void store_background(ivec2 pixel) {
    imageStore(hdr_image, pixel, vec4(background_radiance(pixel), 0.0));
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
