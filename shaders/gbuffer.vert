#version 460
// G-buffer pass: world-space vertices (flattened at load time) to clip space.
#extension GL_GOOGLE_include_directive : require

#include "draw_constants.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;  // xyz, w: bitangent sign (zero: none)
layout(location = 4) in vec4 in_color;    // COLOR_0 (white: none)

layout(location = 0) out vec3 out_position;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_tangent;
layout(location = 4) out vec4 out_color;

void main() {
    out_position = in_position;
    out_normal = in_normal;
    out_uv = in_uv;
    out_tangent = in_tangent;
    out_color = in_color;
    gl_Position = draw.view_proj * vec4(in_position, 1.0);
}
