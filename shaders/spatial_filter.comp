#version 460
// The real-time mode's spatial filter: the accumulated radiance (history_out)
// averaged over a 5x5 neighbourhood with weights that keep edges (normals
// and positions must agree), into hdr_image for tone mapping. The filter
// fades out as the history grows and is gone after temporal.filter_frames
// frames, so a resting view shows the accumulated, unbiased mean itself.
#extension GL_GOOGLE_include_directive : require

#include "temporal_bindings.glsl"

const int kFilterRadius = 2;

// How much neighbour q's surface is pixel p's: same side, same plane.
float edge_weight(vec3 x, vec3 n, float footprint, ivec2 q) {
    vec4 y = imageLoad(gbuffer_position, q);
    if (y.w == 0.0) return 0.0;
    vec3 m = imageLoad(gbuffer_normal, q).xyz;
    float facing = max(dot(n, m), 0.0);
    facing *= facing;
    facing *= facing;  // (n . m)^4: creases keep their sides
    float off_plane = abs(dot(y.xyz - x, n)) / footprint;
    return facing * exp(-off_plane * off_plane);
}

vec3 filtered(ivec2 pixel, vec3 x, float footprint) {
    vec3 n = imageLoad(gbuffer_normal, pixel).xyz;
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (int dy = -kFilterRadius; dy <= kFilterRadius; ++dy) {
        for (int dx = -kFilterRadius; dx <= kFilterRadius; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (!inside_image(q)) continue;
            float w = edge_weight(x, n, footprint, q);
            sum += w * imageLoad(history_out, q).rgb;
            weight_sum += w;
        }
    }
    return weight_sum > 0.0 ? sum / weight_sum : imageLoad(history_out, pixel).rgb;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!inside_image(pixel)) return;
    vec4 accumulated = imageLoad(history_out, pixel);
    vec4 position = imageLoad(gbuffer_position, pixel);
    if (position.w == 0.0) return;  // background: the lighting pass stored it
    float frames = accumulated.a;
    float keep_noisy = temporal.filter_frames == 0u ? 1.0 : min(frames / float(temporal.filter_frames), 1.0);
    vec3 result = accumulated.rgb;
    if (keep_noisy < 1.0) {
        // A pixel's footprint at its distance: positions off the plane by
        // about a pixel still count as the same surface.
        float footprint = max(4.0 * length(position.xyz - frame.eye) / float(frame.height), 1e-4);
        result = mix(filtered(pixel, position.xyz, footprint), accumulated.rgb, keep_noisy);
    }
    imageStore(hdr_image, pixel, vec4(result, 1.0));
}
