// Upper bounds on what a light-tree cluster can contribute at a point, for
// the bound criterion (lightcuts/device/cluster_bounds.glsl.h, written once
// for the shaders and the CPU evaluator), over the GPU's tree nodes.
#ifndef LC_CLUSTER_BOUNDS_GLSL
#define LC_CLUSTER_BOUNDS_GLSL

#include "common_lighting.glsl"
#include "frame_bindings.glsl"
#include "lightcuts/device/cluster_bounds.glsl.h"
#include "lightcuts/device/octahedral.glsl.h"
#include "material_model.glsl"

// The compact node (loaded once by the caller) and its representative's
// position and range as the bounds see them; effects the scene lacks compile away.
ClusterShape cluster_shape_of(GpuTreeNode node, vec3 rep_position, float rep_range) {
    uint type = node.flags >> kNodeTypeShift;
    ClusterShape c;
    c.directional = kDirectionalLights && type == kLightDirectional;
    c.spot = kSpotLights && type == kLightSpot;
    c.oriented = kOrientedLights && type == kLightOriented;
    c.leaf = node.first_child == kNoChild;
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
