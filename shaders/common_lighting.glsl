// The shading model of editor_client/render/shading_model.h, in float.
// Per light: E = I * color * G; the caller multiplies the sum by f_r = albedo / pi.
#ifndef LC_COMMON_LIGHTING_GLSL
#define LC_COMMON_LIGHTING_GLSL

#include "effects.glsl"
#include "lightcuts/device/gpu_structs.h"

const float kPi = 3.14159265358979323846;
const float kMinDistance = 1e-3;  // shading::kMinDistance

// KHR_lights_punctual range window: clamp(1 - (d/range)^4, 0, 1)^2; range <= 0: none.
float range_window(float distance, float range) {
    if (range <= 0.0) return 1.0;
    float ratio = distance / range;
    float r2 = ratio * ratio;
    float w = clamp(1.0 - r2 * r2, 0.0, 1.0);
    return w * w;
}

// 1 / d^2, kept finite at a shading point that sits on the light.
float inverse_square(float distance_squared) {
    return 1.0 / max(distance_squared, kMinDistance * kMinDistance);
}

// clamp((cos_s - cos_outer) / max(cos_inner - cos_outer, 1e-4), 0, 1)^2, the
// reciprocal precomputed on the CPU as spot_scale.
float spot_attenuation(float cos_spot, float cos_outer, float spot_scale) {
    float a = clamp((cos_spot - cos_outer) * spot_scale, 0.0, 1.0);
    return a * a;
}

// I * color * G for one light (or a cluster through its representative) at
// point x with unit normal n, and `l`, the unit direction towards the light
// (for the material; unused, it compiles away). Effects the scene lacks
// compile away.
vec3 light_irradiance(GpuLight light, vec3 x, vec3 n, out vec3 l) {
    bool positional_lights = kPointLights || kSpotLights;
    if (kDirectionalLights && (!positional_lights || light.type == kLightDirectional)) {
        // Stored directions are unit to float precision only; a sharp lobe notices.
        float len = length(light.direction);
        l = len > 0.0 ? -light.direction / len : vec3(0.0);
        // Directional: G = max(cos_theta, 0), intensity in lux.
        return light.intensity * max(dot(n, -light.direction), 0.0);
    }
    vec3 to_light = light.position - x;
    float d2 = dot(to_light, to_light);
    float d = sqrt(d2);
    // On the light itself there is no direction: cos_theta counts as 0.
    l = d > 0.0 ? to_light / d : vec3(0.0);
    float g = max(dot(n, l), 0.0) * inverse_square(d2);
    if (kRangeWindow) g *= range_window(d, light.range);
    if (kSpotLights && light.type == kLightSpot)
        g *= spot_attenuation(dot(light.direction, -l), light.spot_cos_outer, light.spot_scale);
    return light.intensity * g;
}

#endif
