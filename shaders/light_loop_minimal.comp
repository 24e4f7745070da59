#version 460
// Benchmark baseline, not used for rendering: only the light loop of
// reference mode (point lights, inverse-square Lambert) at points of a plane
// derived from the pixel, with nothing around it. render_throughput_bench
// compares reference mode's lighting pass with this kernel's rate.
#extension GL_GOOGLE_include_directive : require

#include "lightcuts/device/gpu_structs.h"

layout(local_size_x_id = 0, local_size_y_id = 1) in;

layout(std430, set = 0, binding = 0) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D result;

layout(push_constant) uniform Constants {
    uint width;
    uint height;
    uint light_count;
    float extent;  // side of the square the pixels cover
} pc;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(pc.width) || pixel.y >= int(pc.height)) return;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(pc.width, pc.height) - 0.5;
    vec3 x = vec3(uv.x * pc.extent, 0.0, uv.y * pc.extent);
    vec3 e = vec3(0.0);
    for (uint i = 0u; i < pc.light_count; ++i) {
        vec3 to_light = lights[i].position - x;
        float d2 = dot(to_light, to_light);
        // n = +Y, so cos_theta = to_light.y / d.
        e += lights[i].intensity * (max(to_light.y, 0.0) * inversesqrt(d2) / max(d2, 1e-6));
    }
    imageStore(result, pixel, vec4(e, 1.0));
}
