// The paper's error-bound criterion (Sec. 4), shared by its two searches
// (lightcuts_bound_walk.comp, lightcuts_bound_heap.comp): a node is refined
// while its error bound exceeds kErrorRatio x the cut's total estimate,
// colours compared through their largest channel like cpu_evaluator.cpp
// (kErrorRatio comes with the indirect clamp, indirect_clamp.glsl).
#ifndef LC_BOUND_CRITERION_GLSL
#define LC_BOUND_CRITERION_GLSL

#include "cluster_bounds.glsl"
#include "lightcuts_pass.glsl"

float max_channel(vec3 v) { return max(v.x, max(v.y, v.z)); }

// Largest channel of f_r bound x G bound x I_C over a cluster's lights.
float cluster_error_bound(GpuTreeNode node, SurfacePoint p) {
    GpuLight rep = leaf_lights[node.representative];
    return max_channel(response_bound_of(node, rep, p) * node.intensity);
}

#endif
