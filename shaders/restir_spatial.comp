#version 460
// The ReSTIR mode's second dispatch (Bitterli et al. 2020, Alg. 4 and 5):
// each pixel's reservoir after temporal reuse merged with those of kSpatial
// neighbours drawn in a disc around it (kept only on a similar surface:
// similar_surfaces), weights 1/M (biased) or 1/Z (unbiased: only reservoirs
// whose surface could have drawn the survivor count); one shadow ray for the
// survivor, shaded with its W; the result is the next frame's reservoir.
#extension GL_GOOGLE_include_directive : require

#include "restir_bindings.glsl"

const uint kMaxSpatial = 8u;  // RestirSettings' limit (kMaxRestirSpatial)
const float kSpatialRadius = 16.0;  // pixels

// The i-th neighbour drawn for the pixel, or (-1, -1) off the image.
ivec2 spatial_neighbour(ivec2 pixel) {
    float angle = 6.2831853 * restir_uniform();
    float radius = kSpatialRadius * sqrt(restir_uniform());
    ivec2 q = pixel + ivec2(round(radius * vec2(cos(angle), sin(angle))));
    return inside_image(q) && q != pixel ? q : ivec2(-1);
}

// Whether the pixel q (a merged neighbour) could have drawn `light`: its
// p_hat there, and its visibility there where candidates were visibility-tested.
// In uniform control flow.
bool neighbour_could_produce(ivec2 q, uint light, bool needed) {
    SurfacePoint s;
    bool surface = load_surface(needed ? q : ivec2(0), s) && needed;
    GpuLight l = held_light(light, surface);
    bool positive = surface && restir_target(l, s) > 0.0;
    if (kCandidateVisibility) positive = light_visibility(l, s.position, s.normal, positive) > 0.0 && positive;
    return positive;
}

// The reservoir merged with its neighbours' (`merged`: which were, for 1/Z).
Reservoir spatial_reuse(ivec2 pixel, SurfacePoint p, bool surface, GpuReservoir own,
                        out ivec2 merged[kMaxSpatial], out float merged_count[kMaxSpatial]) {
    Reservoir s = empty_reservoir();
    reservoir_offer(s, own.light, own.target * own.weight * own.count, own.count, own.target);
    for (uint i = 0u; i < kSpatial; ++i) {
        merged[i] = ivec2(-1);
        merged_count[i] = 0.0;
        ivec2 q = spatial_neighbour(pixel);
        if (!surface || q.x < 0) continue;
        GpuReservoir other = reservoirs_temporal[reservoir_index(q)];
        if (!(other.count > 0.0) || !similar_surfaces(p.position, p.normal, other.position, other.normal)) continue;
        float target = other.weight > 0.0 ? restir_target(leaf_lights[other.light], p) : 0.0;
        reservoir_offer(s, other.light, target * other.weight * other.count, other.count, target);
        merged[i] = q;
        merged_count[i] = other.count;
    }
    return s;
}

// 1/Z's Z: the pixel's own M and each merged neighbour's that could have
// drawn the survivor. In uniform control flow.
float unbiased_normaliser(Reservoir s, float own_count, ivec2 merged[kMaxSpatial], float merged_count[kMaxSpatial]) {
    float z = own_count;
    for (uint i = 0u; i < kSpatial; ++i) {
        bool counted = neighbour_could_produce(merged[i], s.light, s.has_sample && merged[i].x >= 0);
        if (counted) z += merged_count[i];
    }
    return z;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = pixel.x < int(frame.width) && pixel.y < int(frame.height);
    SurfacePoint p;
    // Lanes off the image walk the shared shadow rays for pixel (0, 0) and store nothing.
    ivec2 at = inside ? pixel : ivec2(0);
    bool surface = load_surface(at, p) && inside;
    seed_restir_random(pixel, frame.frame_seed, 1u);
    GpuReservoir own = reservoirs_temporal[reservoir_index(at)];
    ivec2 merged[kMaxSpatial];
    float merged_count[kMaxSpatial];
    Reservoir s = spatial_reuse(pixel, p, surface, own, merged, merged_count);
    float normaliser = kUnbiased ? unbiased_normaliser(s, own.count, merged, merged_count) : s.count;
    float weight = contribution_weight(s, normaliser);
    // The survivor's shadow ray, and its radiance.
    bool shaded = surface && weight > 0.0;
    GpuLight light = held_light(s.light, shaded);
    vec3 l;
    vec3 c = shaded ? unshadowed_radiance(light, p, l) : vec3(0.0);
    bool lit = max(c.x, max(c.y, c.z)) > 0.0;
    if (kShadows) c *= light_visibility(light, p.position, p.normal, lit);
    if (!inside) {
        flush_pixel_counters(false);
        return;
    }
    reservoirs_final[reservoir_index(pixel)] = stored_reservoir(s, weight, p.position, p.normal);
    if (!surface) {
        flush_pixel_counters(false);
        store_background(pixel);
        return;
    }
    vec3 radiance = c * weight + classic_and_emitted_radiance(p);
    store_pixel(pixel, radiance, 1u, s.has_sample ? cut_hash_term(s.light) : 0u, g_shadow_walk_cut_short);
}
