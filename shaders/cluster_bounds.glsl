// Upper bounds on what a light-tree cluster can contribute at a point, for
// the bound criterion (lightcuts/device/cluster_bounds.glsl.h, written once
// for the shaders and the CPU evaluator), over the GPU's tree nodes.
#ifndef LC_CLUSTER_BOUNDS_GLSL
#define LC_CLUSTER_BOUNDS_GLSL

#include "common_lighting.glsl"
#include "frame_bindings.glsl"
#include "lightcuts/device/cluster_bounds.glsl.h"
#include "material_model.glsl"

// lightcuts/tree/compact_node.h's octahedral unit vector (2 x snorm16).
vec3 decode_octahedral(uint bits) {
    vec2 e = unpackSnorm2x16(bits);
    vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (v.z < 0.0) {
        vec2 sign_not_zero = mix(vec2(1.0), vec2(-1.0), lessThan(e, vec2(0.0)));
        v.xy = (1.0 - abs(e.yx)) * sign_not_zero;
    }
    return normalize(v);
}

// The compact node (loaded once by the caller) and its representative's
// position and range as the bounds see them; effects the scene lacks compile away.
ClusterShape cluster_shape_of(GpuTreeNode node, vec3 rep_position, float rep_range) {
    uint type = node.flags >> kNodeTypeShift;
    ClusterShape c;
    c.directional = kDirectionalLights && type == kLightDirectional;
    c.spot = kSpotLights && type == kLightSpot;
    c.oriented = kOrientedLights && type == kLightOriented;
    c.leaf = node.first_child == kEndOfWalk;
    c.bbox_min = node.bbox_min;
    c.bbox_max = node.bbox_max;
    c.position = rep_position;
    c.range = rep_range;
    c.radius = node.radius;
    c.cone_axis = decode_octahedral(node.cone_axis);
    c.cone_cos = node.cone_cos;
    return c;
}

// Upper bound of f_r x G (visibility 1) per unit intensity over a node's lights.
vec3 response_bound_of(GpuTreeNode node, vec3 rep_position, float rep_range, SurfacePoint p) {
    return response_bound(cluster_shape_of(node, rep_position, rep_range), p.albedo, p.specular, p.exponent, p.mirror,
                          p.position, p.normal);
}

#endif
