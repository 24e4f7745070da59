// Push constants of one G-buffer draw; mirrors GpuDrawConstants in gpu_layout.h.
#ifndef LC_DRAW_CONSTANTS_GLSL
#define LC_DRAW_CONSTANTS_GLSL

const uint kDrawBaseColorTexture = 1u;
const uint kDrawEmissiveTexture = 2u;
const uint kDrawMetallicRoughnessTexture = 4u;

layout(push_constant) uniform DrawConstants {
    mat4 view_proj;
    vec4 base_color_factor;
    vec4 emissive_metallic;  // rgb: emissive factor, a: metallic
    vec4 eye_roughness;      // xyz: camera position, w: roughness
    uint flags;
    uint pad0;
    uint pad1;
    uint pad2;
} draw;

#endif
