#version 460
// G-buffer pass: world position (w = 1 marks geometry), shading normal (a
// double-sided surface's back face reversed; a single-sided one's culled), base colour x texture
// (the sRGB texture format decodes on sampling), metallic/roughness, emissive.
#extension GL_GOOGLE_include_directive : require

#include "draw_constants.glsl"
#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"

layout(constant_id = kSpecTextures) const bool kTextures = true;

layout(set = 0, binding = kBindBaseColorTexture) uniform sampler2D base_color_texture;
layout(set = 0, binding = kBindEmissiveTexture) uniform sampler2D emissive_texture;
layout(set = 0, binding = kBindMetallicRoughnessTexture) uniform sampler2D metallic_roughness_texture;  // linear: G, B
layout(set = 0, binding = kBindNormalTexture) uniform sampler2D normal_texture;  // linear, tangent space

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec4 in_color;  // COLOR_0, times the base colour

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec4 out_emissive;

// The normal map's normal in the frame of the interpolated normal `base`
// (unit, as the file orients it) and tangent; glTF's tangent space: x along
// the tangent, y along cross(normal, tangent) * w. Seen from the back, the
// whole frame turns round with the normal. `texel`: the map's RGB.
vec3 mapped_normal(vec3 base, bool back, vec3 texel) {
    vec3 t = in_tangent.xyz - base * dot(base, in_tangent.xyz);
    if (dot(t, t) < 1e-24) return back ? -base : base;
    t = normalize(t);
    vec3 b = cross(base, t) * (in_tangent.w < 0.0 ? -1.0 : 1.0);
    vec3 s = texel * 2.0 - 1.0;
    s.xy *= draw.normal_scale;
    vec3 m = t * s.x + b * s.y + base * s.z;
    float len = length(m);
    m = len > 0.0 ? m / len : base;
    return back ? -m : m;
}

void main() {
    // Derivatives are taken in uniform control flow, before any branch.
    vec3 geometric = cross(dFdx(in_position), dFdy(in_position));
    bool has_normal = dot(in_normal, in_normal) > 1e-24;
    vec3 n = has_normal ? in_normal : geometric;
    float len = length(n);
    n = len > 0.0 ? n / len : vec3(0.0, 1.0, 0.0);
    // glTF: a back face (clockwise) is shaded with its normal reversed. The
    // derivatives' normal has no side of its own: it faces the camera.
    bool back = has_normal ? !gl_FrontFacing : dot(n, draw.eye_roughness.xyz - in_position) < 0.0;
    if (back) n = -n;
    if (kTextures && (draw.flags & kDrawNormalTexture) != 0u)
        n = mapped_normal(back ? -n : n, back, texture(normal_texture, in_uv).rgb);

    vec4 base = draw.base_color_factor;
    // Only where the mesh has COLOR_0: an interpolated white may not be exactly 1.
    if ((draw.flags & kDrawVertexColors) != 0u) base *= in_color;
    vec3 emissive = draw.emissive_metallic.rgb;
    float metallic = draw.emissive_metallic.a;
    float roughness = draw.eye_roughness.w;
    if (kTextures) {
        if ((draw.flags & kDrawBaseColorTexture) != 0u) base *= texture(base_color_texture, in_uv);
        if ((draw.flags & kDrawEmissiveTexture) != 0u)
            emissive *= texture(emissive_texture, in_uv).rgb;
        if ((draw.flags & kDrawMetallicRoughnessTexture) != 0u) {
            vec4 mr = texture(metallic_roughness_texture, in_uv);
            roughness *= mr.g;
            metallic *= mr.b;
        }
    }
    // alphaMode MASK: cut out where alpha is under the cutoff (after every
    // texture fetch, so the derivatives above stay in uniform control flow).
    if ((draw.flags & kDrawAlphaMask) != 0u && base.a < draw.alpha_cutoff) discard;
    // doubleSided false: the back face is culled (per primitive, so per quad).
    if ((draw.flags & kDrawSingleSided) != 0u && !gl_FrontFacing) discard;
    out_position = vec4(in_position, 1.0);
    out_normal = vec4(n, roughness);
    out_albedo = vec4(base.rgb, metallic);
    out_emissive = vec4(emissive, 1.0);
}
