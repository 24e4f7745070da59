// What the ReSTIR mode's two dispatches share (restir_candidates.comp,
// restir_spatial.comp): the frame's set 0 and the lighting helpers, the
// temporal history's set 1 (the previous camera), the light-draw records'
// set 2, the pass's reservoirs (set kRestirSet, lightcuts/device/restir.h)
// and the mode's specialization constants.
#ifndef LC_RESTIR_BINDINGS_GLSL
#define LC_RESTIR_BINDINGS_GLSL

#extension GL_KHR_shader_subgroup_vote : require

#include "lighting_pass.glsl"
#include "restir_reservoir.glsl"
#include "stochastic_draw.glsl"
#include "temporal_bindings.glsl"

layout(constant_id = kSpecRestirCandidates) const uint kCandidates = 16u;
layout(constant_id = kSpecRestirSource) const uint kSource = kRestirSourceTree;
layout(constant_id = kSpecRestirSpatial) const uint kSpatial = 3u;
layout(constant_id = kSpecRestirTemporal) const bool kTemporal = true;
layout(constant_id = kSpecRestirUnbiased) const bool kUnbiased = false;
layout(constant_id = kSpecRestirCandidateVisibility) const bool kCandidateVisibility = false;

layout(std430, set = kRestirSet, binding = kBindReservoirsPrevious) readonly buffer ReservoirsPrevious {
    GpuReservoir reservoirs_previous[];
};
layout(std430, set = kRestirSet, binding = kBindReservoirsTemporal) buffer ReservoirsTemporal {
    GpuReservoir reservoirs_temporal[];
};
layout(std430, set = kRestirSet, binding = kBindReservoirsFinal) writeonly buffer ReservoirsFinal {
    GpuReservoir reservoirs_final[];
};

uint reservoir_index(ivec2 pixel) { return uint(pixel.y) * frame.width + uint(pixel.x); }

// Leaf light i, read only where a reservoir holds one (with no lights the
// buffer holds none): a caller with `has` false uses nothing of it.
GpuLight held_light(uint i, bool has) {
    GpuLight light;
    if (has) light = leaf_lights[i];
    return light;
}

// The light's unshadowed radiance towards the camera at p (0 behind the surface).
vec3 unshadowed_radiance(GpuLight light, SurfacePoint p, out vec3 l) {
    vec3 e = light_irradiance(light, p.position, p.normal, l);
    return brdf_toward(p, l) * e;
}

// The target function p_hat: that radiance's luminance.
float restir_target(GpuLight light, SurfacePoint p) {
    vec3 l;
    float y = dot(unshadowed_radiance(light, p, l), vec3(0.2126, 0.7152, 0.0722));
    return y > 0.0 && y < 3.402823466e38 ? y : 0.0;
}

// Whether two surfaces are alike enough to share reservoirs: normals within
// about 25 degrees, distances from the eye within 10%.
bool similar_surfaces(vec3 x, vec3 n, vec3 y, vec3 m) {
    float dx = distance(x, frame.eye);
    return dot(n, m) > 0.9 && abs(distance(y, frame.eye) - dx) <= 0.1 * dx;
}

#endif
