#version 460
// Linear HDR radiance to display values: exposure, filmic curve, sRGB encode.
#extension GL_GOOGLE_include_directive : require

#include "frame_bindings.glsl"
#include "tone_mapping.glsl"

layout(local_size_x_id = kSpecWorkgroupX, local_size_y_id = kSpecWorkgroupY) in;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
    vec3 radiance = imageLoad(hdr_image, pixel).rgb;
    imageStore(display_image, pixel, vec4(srgb_encode(filmic(radiance * frame.exposure)), 1.0));
}
