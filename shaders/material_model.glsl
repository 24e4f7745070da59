// The material model (lightcuts/device/material.glsl.h, written once for the
// shaders and the CPU evaluator) at a G-buffer's surface point, in float.
#ifndef LC_MATERIAL_MODEL_GLSL
#define LC_MATERIAL_MODEL_GLSL

#include "common_lighting.glsl"
#include "lightcuts/device/material.glsl.h"

// Off when no drawn material has a lobe (scene_effects.cpp): f_r is then the
// constant diffuse / pi and the lobe's code compiles away.
layout(constant_id = kSpecSpecular) const bool kSpecular = true;

struct SurfacePoint {
    vec3 position;
    vec3 normal;
    vec3 albedo;    // diffuse albedo
    vec3 specular;  // F0 of the lobe; 0 when folded into the albedo
    float exponent; // n of the lobe
    vec3 mirror;    // the lobe's axis: the view reflected about the normal
    vec3 emissive;
};

// glTF metallic-roughness to diffuse + lobe. Without lobes to simulate every
// material shades as fully rough: its lobe joins the diffuse term.
void set_material(inout SurfacePoint p, vec3 base_color, float metallic, float roughness,
                  vec3 eye) {
    SurfaceMaterial m = surface_material(base_color, metallic, kSpecular ? roughness : 1.0);
    p.albedo = m.diffuse;
    p.specular = m.specular;
    p.exponent = m.exponent;
    p.mirror = mirror_direction(p.normal, p.position, eye);
}

bool has_lobe(SurfacePoint p) { return kSpecular && has_lobe(p.specular, p.exponent); }

// f_r towards the unit direction l.
vec3 brdf_toward(SurfacePoint p, vec3 l) {
    if (!kSpecular) return diffuse_brdf(p.albedo);
    return brdf(p.albedo, p.specular, p.exponent, p.mirror, l);
}

#endif
