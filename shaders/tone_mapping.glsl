// The tone curve of lightcuts/tone_mapping.h, in GLSL.
#ifndef LC_TONE_MAPPING_GLSL
#define LC_TONE_MAPPING_GLSL

// ACES filmic fit (Narkowicz 2015), clamped to [0, 1].
vec3 filmic(vec3 x) {
    x = max(x, vec3(0.0));
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 srgb_encode(vec3 linear) {
    linear = clamp(linear, 0.0, 1.0);
    vec3 low = 12.92 * linear;
    vec3 high = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
    return mix(high, low, lessThanEqual(linear, vec3(0.0031308)));
}

#endif
