// The material model of editor_client/render/material_model.h, in float: a
// Lambert term plus a glossy lobe symmetric about the view's mirror direction,
// and the surface point the lighting passes shade with it.
#ifndef LC_MATERIAL_MODEL_GLSL
#define LC_MATERIAL_MODEL_GLSL

#include "common_lighting.glsl"

// Off when no drawn material has a lobe (scene_effects.cpp): f_r is then the
// constant diffuse / pi and the lobe's code compiles away.
layout(constant_id = kSpecSpecular) const bool kSpecular = true;

const float kDielectricF0 = 0.04;  // shading::kDielectricF0
const float kMinRoughness = 0.1;   // shading::kMinRoughness

struct SurfacePoint {
    vec3 position;
    vec3 normal;
    vec3 albedo;    // diffuse albedo
    vec3 specular;  // F0 of the lobe; 0 when folded into the albedo
    float exponent; // n of the lobe
    vec3 mirror;    // the lobe's axis: the view reflected about the normal
    vec3 emissive;
};

// n = 4 / alpha^2 - 4 with alpha = roughness^2.
float lobe_exponent(float roughness) {
    float r = clamp(roughness, kMinRoughness, 1.0);
    float alpha2 = r * r * r * r;
    return max(4.0 / alpha2 - 4.0, 0.0);
}

// N(n) ((1 + c) / 2)^n, N(n) = (n + 1)(n + 2) / (4 pi (n + 2^-(n+1))); pow is
// only called on a positive base.
float glossy_lobe(float cos_to_mirror, float exponent) {
    float h = clamp((1.0 + cos_to_mirror) * 0.5, 0.0, 1.0);
    float n = exponent;
    float peak = (n + 1.0) * (n + 2.0) / (4.0 * kPi * (n + exp2(-(n + 1.0))));
    if (!(h > 0.0)) return exponent > 0.0 ? 0.0 : peak;
    return peak * pow(h, exponent);
}

// glTF metallic-roughness to diffuse + lobe (shading::surface_material). A
// rough material's lobe is the constant 1/pi and joins the diffuse term; so
// does every lobe when the scene has none to simulate.
void set_material(inout SurfacePoint p, vec3 base_color, float metallic, float roughness,
                  vec3 eye) {
    float m = clamp(metallic, 0.0, 1.0);
    p.albedo = (1.0 - m) * (1.0 - kDielectricF0) * base_color;
    vec3 f0 = kDielectricF0 * (1.0 - m) + m * base_color;
    p.exponent = kSpecular ? lobe_exponent(roughness) : 0.0;
    p.specular = vec3(0.0);
    if (p.exponent > 0.0) {
        p.specular = f0;
    } else {
        p.albedo += f0;
    }
    vec3 to_eye = eye - p.position;
    float len = length(to_eye);
    vec3 v = len > 0.0 ? to_eye / len : p.normal;
    p.mirror = 2.0 * dot(p.normal, v) * p.normal - v;
}

bool has_lobe(SurfacePoint p) {
    return kSpecular && p.exponent > 0.0 && max(p.specular.x, max(p.specular.y, p.specular.z)) > 0.0;
}

// f_r towards the unit direction l.
vec3 brdf_toward(SurfacePoint p, vec3 l) {
    vec3 f = p.albedo * (1.0 / kPi);
    if (has_lobe(p)) f += p.specular * glossy_lobe(dot(p.mirror, l), p.exponent);
    return f;
}

#endif
