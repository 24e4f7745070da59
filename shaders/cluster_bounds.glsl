// Upper bounds on what a light-tree cluster can contribute at a point, for
// the bound criterion (lightcuts/device/cluster_bounds.glsl.h, written once
// for the shaders and the CPU evaluator), over the GPU's tree nodes.
#ifndef LC_CLUSTER_BOUNDS_GLSL
#define LC_CLUSTER_BOUNDS_GLSL

#include "common_lighting.glsl"
#include "frame_bindings.glsl"
#include "lightcuts/device/cluster_bounds.glsl.h"
#include "material_model.glsl"

// The GPU node as the bounds see it (its record and bounds, loaded once by the
// caller); effects the scene lacks compile away.
ClusterShape cluster_shape_of(GpuTreeNode node, GpuNodeBounds nb) {
    ClusterShape c;
    c.directional = kDirectionalLights && node.light.type == kLightDirectional;
    c.spot = kSpotLights && node.light.type == kLightSpot;
    c.leaf = node.first_child == kEndOfWalk;
    c.bbox_min = nb.bbox_min;
    c.bbox_max = nb.bbox_max;
    c.position = node.light.position;
    c.range = node.light.range;
    c.radius = node.radius;
    c.cone_axis = nb.cone_axis;
    c.cone_cos = nb.cone_cos;
    return c;
}

// Upper bound of f_r x G (visibility 1) per unit intensity over a node's lights.
vec3 response_bound_of(GpuTreeNode node, GpuNodeBounds nb, SurfacePoint p) {
    return response_bound(cluster_shape_of(node, nb), p.albedo, p.specular, p.exponent, p.mirror,
                          p.position, p.normal);
}

#endif
