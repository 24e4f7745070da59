#version 460
// Reference mode: every tree leaf (or scene light) plus every classic light,
// summed exactly in float at each pixel with geometry.
#extension GL_GOOGLE_include_directive : require

#include "lighting_pass.glsl"
#include "loop_limits.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1) in;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
    SurfacePoint p;
    if (!load_surface(pixel, p)) {
        store_background(pixel);
        return;
    }
    vec3 irradiance = vec3(0.0);
    uint i = 0u;
    for (; i + kLoopUnroll <= frame.leaf_count; i += kLoopUnroll) {
        irradiance += light_irradiance(leaf_lights[i], p.position, p.normal);
        irradiance += light_irradiance(leaf_lights[i + 1u], p.position, p.normal);
        irradiance += light_irradiance(leaf_lights[i + 2u], p.position, p.normal);
        irradiance += light_irradiance(leaf_lights[i + 3u], p.position, p.normal);
    }
    for (; i < frame.leaf_count; ++i)
        irradiance += light_irradiance(leaf_lights[i], p.position, p.normal);
    irradiance += classic_irradiance(p);
    // Every leaf is in the "cut"; the hash is not needed for reference pixels.
    store_pixel(pixel, outgoing_radiance(p, irradiance), frame.leaf_count, 0u);
}
