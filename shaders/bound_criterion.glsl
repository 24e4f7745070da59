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

// Largest channel of f_r bound x G bound x I_C over a cluster's lights. The
// representative is loaded only when it has a range (its position and range
// bound the cluster): an unbounded node's bound reads the node alone, one
// dependent load less on every node the walk visits.
float cluster_error_bound(GpuTreeNode node, SurfacePoint p) {
    vec3 position = node.bbox_min;  // unread: an unbounded node tests no range
    float range = 0.0;
    if ((node.flags & kNodeBoundedRepresentative) != 0u) {
        position = leaf_lights[node.representative].position;
        range = leaf_lights[node.representative].range;
    }
    return max_channel(response_bound_of(node, position, range, p) * node.intensity);
}

#endif
