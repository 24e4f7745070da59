// The real-time mode's own set (set kTemporalSet, owned by RealtimePass): the
// accumulated history and the world positions it was shaded at, the previous
// frame's (In) and this frame's (Out), and the temporal parameters. The
// frame's set 0 (frame_bindings.glsl) is bound beside it.
#ifndef LC_TEMPORAL_BINDINGS_GLSL
#define LC_TEMPORAL_BINDINGS_GLSL

#include "frame_bindings.glsl"

layout(set = 1, binding = kBindHistoryIn, rgba32f) uniform readonly image2D history_in;
layout(set = 1, binding = kBindHistoryOut, rgba32f) uniform image2D history_out;
layout(set = 1, binding = kBindHistoryPositionIn, rgba32f) uniform readonly image2D history_position_in;
layout(set = 1, binding = kBindHistoryPositionOut, rgba32f) uniform writeonly image2D history_position_out;
layout(std430, set = 1, binding = kBindTemporalParams) readonly buffer TemporalParams {
    GpuTemporalParams temporal;
};

layout(local_size_x_id = kSpecWorkgroupX, local_size_y_id = kSpecWorkgroupY) in;

bool inside_image(ivec2 pixel) {
    return pixel.x >= 0 && pixel.y >= 0 && pixel.x < int(frame.width) && pixel.y < int(frame.height);
}

// Where the world position x was in the previous frame, in pixels; false
// outside its image or behind its camera.
bool previous_pixel(vec3 x, out ivec2 pixel) {
    vec4 clip = temporal.previous_view_proj * vec4(x, 1.0);
    pixel = ivec2(-1);
    if (!(clip.w > 0.0)) return false;
    vec2 ndc = clip.xy / clip.w;
    vec2 at = (ndc * 0.5 + 0.5) * vec2(frame.width, frame.height);
    if (!(at.x >= 0.0 && at.y >= 0.0)) return false;
    pixel = ivec2(at);
    return inside_image(pixel);
}

#endif
