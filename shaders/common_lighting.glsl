// The shading model (lightcuts/device/shading.glsl.h, written once for the
// shaders and the CPU evaluator) for a GPU light, in float.
// Per light: E = I * color * G; the caller multiplies it by f_r.
#ifndef LC_COMMON_LIGHTING_GLSL
#define LC_COMMON_LIGHTING_GLSL

#include "effects.glsl"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/device/shading.glsl.h"

// The GPU light as G sees it; effects the scene lacks compile away.
Emitter emitter_of(GpuLight light) {
    Emitter e;
    bool positional_lights = kPointLights || kSpotLights || kOrientedLights;
    e.directional = kDirectionalLights && (!positional_lights || light.type == kLightDirectional);
    e.spot = kSpotLights && light.type == kLightSpot;
    e.oriented = kOrientedLights && light.type == kLightOriented;
    e.position = light.position;
    e.direction = light.direction;
    e.range = kRangeWindow ? light.range : 0.0;
    e.cos_outer = light.spot_cos_outer;
    e.spot_scale = light.spot_scale;
    e.source_radius = kOrientedLights ? light.source_radius : 0.0;
    return e;
}

// I * color * G for one light (or a cluster through its representative) at
// point x with unit normal n, and `l`, the unit direction towards the light
// (for the material; unused, it compiles away).
vec3 light_irradiance(GpuLight light, vec3 x, vec3 n, out vec3 l) {
    return light.intensity * light_geometry(emitter_of(light), x, n, l);
}

#endif
