#version 460
// The real-time mode's temporal pass: this frame's noisy estimate (hdr_image,
// realtime_lighting.comp) joins the pixel's history. While the view rests the
// history is the pixel's own and the result is the running mean of every
// frame since the view last changed: it converges to the unbiased answer.
// While the camera moves, the history is found where the pixel's surface was
// in the previous frame (reprojection), dropped where that is another surface
// (disocclusion), clamped to this frame's 3x3 neighbourhood (no ghosting) and
// kept short.
#extension GL_GOOGLE_include_directive : require

#include "temporal_bindings.glsl"

// The pixel's history: the previous frame's accumulation of the same surface,
// or nothing (a = 0).
vec4 find_history(ivec2 pixel, vec3 x) {
    if (temporal.history_valid == 0u) return vec4(0.0);
    ivec2 from = pixel;
    if (temporal.camera_moved != 0u && !previous_pixel(x, from)) return vec4(0.0);
    vec4 was_at = imageLoad(history_position_in, from);
    float tolerance = temporal.position_tolerance * max(length(x - frame.eye), 1e-4);
    if (was_at.w == 0.0 || distance(was_at.xyz, x) > tolerance) return vec4(0.0);
    return imageLoad(history_in, from);
}

// The history limited to what this frame's neighbourhood shows: a moved
// history may hold another surface's light.
vec3 clamp_to_neighbourhood(ivec2 pixel, vec3 history) {
    vec3 lo = vec3(uintBitsToFloat(0x7f800000u));
    vec3 hi = -lo;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (!inside_image(q) || imageLoad(gbuffer_position, q).w == 0.0) continue;
            vec3 c = imageLoad(hdr_image, q).rgb;
            lo = min(lo, c);
            hi = max(hi, c);
        }
    }
    return clamp(history, lo, hi);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!inside_image(pixel)) return;
    vec4 position = imageLoad(gbuffer_position, pixel);
    vec3 current = imageLoad(hdr_image, pixel).rgb;
    imageStore(history_position_out, pixel, position);
    if (position.w == 0.0) {
        imageStore(history_out, pixel, vec4(current, 0.0));
        return;
    }
    vec4 history = find_history(pixel, position.xyz);
    bool moved = temporal.camera_moved != 0u;
    uint cap = moved ? temporal.moving_history_cap : temporal.still_history_cap;
    float frames = min(history.a, float(cap));
    vec3 kept = moved && frames > 0.0 ? clamp_to_neighbourhood(pixel, history.rgb) : history.rgb;
    // The running mean: with n frames kept, the new one weighs 1 / (n + 1).
    vec3 mean = kept + (current - kept) / (frames + 1.0);
    imageStore(history_out, pixel, vec4(mean, frames + 1.0));
}
