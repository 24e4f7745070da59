#version 460
// Lightcuts: per pixel, select a cut of the light tree and evaluate each cut
// node as a cluster (its representative's position, direction, range and spot
// cone with the cluster's RGB intensity); classic lights are added one by one.
//
// Cut selection depends on the criterion:
//   radius (the thesis): a stackless pre-order walk (first child / escape
//     indices from gpu_layout.h) that a subgroup shares. A node is refined
//     while the point lies strictly inside its influence radius (radius < 0:
//     unbounded, always inside) and it has children; mixed-type junctions are
//     always refined. Every step moves forward in pre-order, so a chain of
//     depth N costs at most N steps and there is no stack to overflow.
//   bound (the paper, not implemented yet; the host refuses it): will keep a
//     bounded max-heap of (node, estimate, bound) entries, at most max-cut of
//     them, in private memory, refining the largest bound until every bound is
//     <= error x total. It becomes select_cut_bound(), fills the same Cut with
//     add_to_cut, reads GpuNodeBounds from a new binding, and main() picks it
//     with a specialization constant (id 8 is reserved for the criterion).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require

#include "cut_hash.glsl"
#include "lighting_pass.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1) in;

struct Cut {
    vec3 irradiance;  // sum over cut nodes of I_C * color * G
    uint size;
    uint hash;
};

void add_to_cut(inout Cut cut, uint node_index, GpuLight cluster, SurfacePoint p) {
    cut.irradiance += light_irradiance(cluster, p.position, p.normal);
    cut.size += 1u;
    cut.hash += cut_hash_term(node_index);
}

// Reads only what the decision needs: most steps of a walk refine, and a
// node's light is loaded only when the node joins the cut.
bool refine_by_radius(int i, vec3 x) {
    if (tree_nodes[i].first_child == kEndOfWalk) return false;
    if ((tree_nodes[i].flags & kNodeMixedTypes) != 0u) return true;
    float radius = tree_nodes[i].radius;
    if (radius < 0.0) return true;
    vec3 d = x - tree_nodes[i].light.position;
    return dot(d, d) < radius * radius;
}

// The subgroup walks the union of its pixels' cuts in pre-order, every lane at
// the same node, so node reads are uniform and nothing diverges but the
// evaluation itself. The subgroup descends when any active lane refines; a
// lane that takes a node as a cluster sits out the node's subtree, waiting for
// the walk to reach the node's escape (the walk only moves forward in
// pre-order and never jumps past an escape of a node it is inside). Each lane
// still gets exactly its own cut.
Cut select_cut_radius(SurfacePoint p) {
    Cut cut = Cut(vec3(0.0), 0u, 0u);
    int i = frame.node_count > 0u ? 0 : kEndOfWalk;
    bool waiting = false;
    int resume = kEndOfWalk;
    // node_count steps always suffice; the limit only guards a corrupt upload.
    for (uint step = 0u; i != kEndOfWalk && step < frame.node_count; ++step) {
        if (waiting && i == resume) waiting = false;
        bool refine = !waiting && refine_by_radius(i, p.position);
        if (!waiting && !refine) {
            add_to_cut(cut, uint(i), tree_nodes[i].light, p);
            waiting = true;
            resume = tree_nodes[i].escape;
        }
        i = subgroupAny(refine) ? tree_nodes[i].first_child : tree_nodes[i].escape;
    }
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
    Cut cut = select_cut_radius(p);
    vec3 irradiance = cut.irradiance + classic_irradiance(p);
    store_pixel(pixel, outgoing_radiance(p, irradiance), cut.size, cut.hash);
}
