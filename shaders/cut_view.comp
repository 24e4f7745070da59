#version 460
// Visualises the cuts the lighting pass chose (display values, no tone curve):
//   cuts:    each distinct cut a stable colour derived from its hash;
//   cutsize: heatmap of cut nodes per pixel, scaled by the frame's largest cut,
//            with a colour scale bar (0 on the left, max on the right) in the
//            bottom scale_bar_rows rows.
// Pixels without geometry are black.
#extension GL_GOOGLE_include_directive : require

#include "frame_bindings.glsl"

layout(local_size_x_id = kSpecWorkgroupX, local_size_y_id = kSpecWorkgroupY) in;

layout(constant_id = kSpecCutView) const uint kView = kCutViewCuts;

// Re-mixes the (additive) cut hash so similar sums get unrelated colours.
uint mix_hash(uint h) {
    h ^= h >> 17;
    h *= 0xed5ad4bbu;
    h ^= h >> 11;
    h *= 0xac4c1b51u;
    h ^= h >> 15;
    return h;
}

vec3 hsv_to_rgb(float h, float s, float v) {
    vec3 k = clamp(abs(mod(h * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
    return v * mix(vec3(1.0), k, s);
}

vec3 cut_colour(uint cut_hash) {
    uint h = mix_hash(cut_hash);
    float hue = float(h & 0xffffu) / 65536.0;
    float saturation = 0.55 + 0.4 * float((h >> 16) & 0xffu) / 255.0;
    float value = 0.7 + 0.3 * float(h >> 24) / 255.0;
    return hsv_to_rgb(hue, saturation, value);
}

// Dark blue -> blue -> green -> yellow -> red for t in [0, 1].
vec3 heat_colour(float t) {
    const vec3 stops[5] =
        vec3[5](vec3(0.05, 0.03, 0.35), vec3(0.0, 0.45, 1.0), vec3(0.1, 0.85, 0.35),
                vec3(1.0, 0.9, 0.0), vec3(0.95, 0.1, 0.05));
    float x = clamp(t, 0.0, 1.0) * 4.0;
    int i = min(int(x), 3);
    return mix(stops[i], stops[i + 1], x - float(i));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
    vec3 colour = vec3(0.0);
    if (kView == kCutViewCutSize && uint(pixel.y) + frame.scale_bar_rows >= frame.height) {
        // The scale bar, with a one-pixel black line above it.
        bool separator = uint(pixel.y) + frame.scale_bar_rows == frame.height;
        float t = frame.width > 1u ? float(pixel.x) / float(frame.width - 1u) : 0.0;
        colour = separator ? vec3(0.0) : heat_colour(t);
    } else if (imageLoad(gbuffer_position, pixel).w != 0.0) {
        uvec2 cut = imageLoad(cut_image, pixel).xy;
        if (kView == kCutViewCuts) {
            colour = cut_colour(cut.y);
        } else {
            colour = heat_colour(float(cut.x) / float(max(counters.max_cut, 1u)));
        }
    }
    imageStore(display_image, pixel, vec4(colour, 1.0));
}
