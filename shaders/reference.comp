#version 460
// Reference mode: every tree leaf (or scene light) plus every classic light,
// summed exactly in float at each pixel with geometry, each light with its
// shadow ray when the scene has shadows. One dispatch sums the leaves
// [light_begin, light_end) onto the previous dispatches' partial sum, so that
// no invocation exceeds llvmpipe's loop budget (Renderer::reference_chunk):
// the first dispatch adds the classic lights and emission, the last one
// stores the pixel with its checks and counters.
#extension GL_GOOGLE_include_directive : require

#include "lighting_pass.glsl"

layout(local_size_x_id = kSpecWorkgroupX, local_size_y_id = kSpecWorkgroupY) in;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
    SurfacePoint p;
    if (!load_surface(pixel, p)) {
        store_background(pixel);
        return;
    }
    const bool first = frame.light_begin == 0u;
    const bool last = frame.light_end >= frame.leaf_count;
    vec3 radiance = vec3(0.0);
    uint i = frame.light_begin;
    uint end = min(frame.light_end, frame.leaf_count);
    for (; i + kLoopUnroll <= end; i += kLoopUnroll) {
        radiance += light_radiance(leaf_lights[i], p);
        radiance += light_radiance(leaf_lights[i + 1u], p);
        radiance += light_radiance(leaf_lights[i + 2u], p);
        radiance += light_radiance(leaf_lights[i + 3u], p);
    }
    for (; i < end; ++i) radiance += light_radiance(leaf_lights[i], p);
    radiance += first ? classic_and_emitted_radiance(p) : imageLoad(hdr_image, pixel).rgb;
    if (last) {
        // Every leaf is in the "cut"; the hash is not needed for reference pixels.
        store_pixel(pixel, radiance, frame.leaf_count, 0u, false);
    } else {
        imageStore(hdr_image, pixel, vec4(radiance, 1.0));
        flush_pixel_counters(false);
    }
}
