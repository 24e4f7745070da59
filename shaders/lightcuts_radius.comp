#version 460
// Lightcuts with the thesis's radius criterion: a stackless pre-order walk
// (first child / escape indices, lightcuts/tree/gpu_layout.h) that a subgroup
// shares. A node is refined while the point lies strictly inside its influence
// radius (radius < 0: unbounded, always inside) and it has children;
// mixed-type junctions are always refined. Every step moves forward in
// pre-order, so a chain of depth N costs at most N steps and there is no
// stack to overflow.
#extension GL_GOOGLE_include_directive : require

#include "lightcuts_pass.glsl"

// Reads only what the decision needs: most steps of a walk refine, and a
// node's light is loaded only when the node joins the cut.
bool refine_by_radius(int i, vec3 x) {
    if (tree_nodes[i].first_child == kNoChild) return false;
    if ((tree_nodes[i].flags & kNodeMixedTypes) != 0u) return true;
    float radius = tree_nodes[i].radius;
    if (radius < 0.0) return true;
    vec3 d = x - leaf_lights[tree_nodes[i].representative].position;
    return dot(d, d) < radius * radius;
}

// The subgroup walks the union of its pixels' cuts in pre-order, every lane at
// the same node, so node reads are uniform and nothing diverges but the
// evaluation itself. The subgroup descends when any active lane refines; a
// lane that takes a node as a cluster sits out the node's subtree, waiting for
// the walk to reach the node's escape (the walk only moves forward in
// pre-order and never jumps past an escape of a node it is inside). Each lane
// still gets exactly its own cut.
// One step of the walk. Written as a function and called kRadiusUnroll times per
// loop iteration: llvmpipe limits the loop iterations of an invocation
// (lightcuts/device/limits.h), not the straight-line steps inside one.
void radius_walk_step(inout int i, inout bool waiting, inout int resume, inout Cut cut, SurfacePoint p) {
    if (i == kEndOfWalk) return;  // i is the same on every lane of the subgroup
    if (waiting && i == resume) waiting = false;
    if (!waiting && left_out(tree_nodes[i].flags)) {
        waiting = true;
        resume = tree_nodes[i].escape;
    }
    bool refine = !waiting && refine_by_radius(i, p.position);
    if (!waiting && !refine) {
        add_to_cut(cut, uint(i), tree_nodes[i], p);
        waiting = true;
        resume = tree_nodes[i].escape;
    }
    i = subgroupAny(refine) ? tree_nodes[i].first_child : tree_nodes[i].escape;
}

// `cut_short`: the walk did not reach its end (the device's loop limit).
Cut select_cut_radius(SurfacePoint p, out bool cut_short) {
    Cut cut = empty_cut();
    int i = frame.node_count > 0u ? 0 : kEndOfWalk;
    bool waiting = false;
    int resume = kEndOfWalk;
    // node_count steps always suffice; the limit only guards a corrupt upload.
    for (uint step = 0u; i != kEndOfWalk && step < frame.node_count; step += kRadiusUnroll) {
        radius_walk_step(i, waiting, resume, cut, p);
        radius_walk_step(i, waiting, resume, cut, p);
        radius_walk_step(i, waiting, resume, cut, p);
        radius_walk_step(i, waiting, resume, cut, p);
        radius_walk_step(i, waiting, resume, cut, p);
        radius_walk_step(i, waiting, resume, cut, p);
        radius_walk_step(i, waiting, resume, cut, p);
        radius_walk_step(i, waiting, resume, cut, p);
    }
    cut_short = i != kEndOfWalk;
    return cut;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
    SurfacePoint p;
    if (!load_surface(pixel, p)) {
        store_background(pixel);
        return;
    }
    bool walk_cut_short;
    Cut cut = select_cut_radius(p, walk_cut_short);
    store_pixel(pixel, clamp_indirect(pixel, cut.radiance, cut.indirect) + classic_and_emitted_radiance(p),
                cut.size, cut.hash, walk_cut_short);
}
