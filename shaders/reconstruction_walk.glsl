// A pixel's reconstruction cut from its block's four corner samples (Walter
// et al. 2005, Sec. 7, on the GPU): a pre-order walk of the light tree, shared
// by the subgroup like the bound walk, that follows each sample's recorded
// cut with a cursor. At a node, each sample has recorded it (on its cut),
// recorded an ancestor of it (its visibility stands for the node's), or cut
// below it. The rules, in order:
//  - refine where some sample cut below the node (its cut is finer there);
//  - discard a node that no sample saw lit and some saw blocked (the others
//    saw it add nothing: behind their surface, outside a spot's cone);
//  - refine where the node's error bound at this pixel exceeds the error
//    ratio times the samples' interpolated total (a light close to this
//    pixel, the paper's "much brighter" case);
//  - otherwise evaluate the cluster here, as a lightcut does, but trace its
//    shadow ray only where the samples do not all see it: where they agree
//    the pixel takes their visibility (the paper interpolates an impostor
//    instead; shading the cluster here keeps the pixel's own material and
//    distance, and costs no ray).
#ifndef LC_RECONSTRUCTION_WALK_GLSL
#define LC_RECONSTRUCTION_WALK_GLSL

#include "bound_criterion.glsl"
#include "reconstruction_bindings.glsl"

// A sample's cursor is inside none of its cut nodes' subtrees (kEndOfWalk is
// an escape, so it cannot mark this).
const int kNotInside = -2;

// Per corner sample: the next record, one past its last, the escape of the
// cut node whose subtree the walk is in (kNotInside: none) and what that
// node's shadow ray said.
uint g_next_record[4];
uint g_end_record[4];
int g_inside_until[4];
uint g_inside_seen[4];

// A pixel's cut holds at least the union of its corners' cuts, each up to
// max-cut: with the same limit the union of cuts that stopped there would
// send the pixel to a lightcut of its own, which stops there again. Its
// nodes mostly cost no ray, so it may grow to four corners' worth.
const uint kReconstructionMaxCut = 4u * kWalkMaxCut;

struct ReconstructionCut {
    vec3 radiance;
    uint size;
    uint hash;
    bool over;  // more than kReconstructionMaxCut nodes: the pixel runs a lightcut instead
    IndirectSums indirect;
};

void begin_sample_cursor(uint k, uint sample_index) {
    g_next_record[k] = first_record_of(sample_index);
    g_end_record[k] = g_next_record[k] + min(samples[sample_index].record_count, kRecordCap);
    g_inside_until[k] = kNotInside;
    g_inside_seen[k] = kSeenDark;
}

// Where sample k stands at node i (the walk visits nodes in pre-order, as the
// samples wrote them): its kSeen* for the node, or `below` when its cut is
// finer here. Takes the node's record when it is the sample's next one.
uint sample_view(uint k, int i, int escape, inout bool below) {
    if (g_inside_until[k] != kNotInside) return g_inside_seen[k];
    if (g_next_record[k] < g_end_record[k]) {
        uint record = read_record(g_next_record[k]);
        if ((record >> kSeenBits) == uint(i)) {
            ++g_next_record[k];
            g_inside_until[k] = escape;
            g_inside_seen[k] = record & ((1u << kSeenBits) - 1u);
            return g_inside_seen[k];
        }
    }
    below = true;
    return kSeenDark;
}

// The cluster shaded here; its ray traced when the samples disagree
// (`disagree`) or when, unshadowed, it alone would exceed tau here: taking
// the samples' visibility of such a cluster risks more than the pixel's
// error bound (a thin shadow between samples that all see the light). Call
// it where bound_walk_step shades (subgroup-shared rays).
vec3 reconstructed_radiance(int i, GpuTreeNode node, SurfacePoint p, bool disagree, float tau) {
    GpuLight light = cluster_light(i, node, p);
    vec3 l;
    vec3 e = light_irradiance(light, p.position, p.normal, l);
    vec3 unshadowed = brdf_toward(p, l) * e;
    bool lit = max(e.x, max(e.y, e.z)) > 0.0;
    bool trace = disagree || max_channel(unshadowed) > tau;
    float v = kShadows ? light_visibility(light, p.position, p.normal, lit && trace) : 1.0;
    return unshadowed * v;
}

// One step of the walk, shared by the subgroup like bound_walk_step: a lane
// that takes a node waits for the walk to leave its subtree.
void reconstruction_step(inout int i, inout bool waiting, inout int resume, inout ReconstructionCut cut,
                         float tau, SurfacePoint p) {
    if (i == kEndOfWalk) return;
    for (uint k = 0u; k < 4u; ++k) {
        if (g_inside_until[k] == i) g_inside_until[k] = kNotInside;
    }
    if (waiting && i == resume) waiting = false;
    GpuTreeNode node = tree_nodes[i];
    if (!waiting && left_out(node.flags)) {
        waiting = true;
        resume = node.escape;
    }
    bool refine = false;
    if (!waiting) {
        bool leaf = node.first_child == kNoChild;
        bool below = false;
        bool all_visible = true;
        bool any_visible = false;
        bool any_blocked = false;
        for (uint k = 0u; k < 4u; ++k) {
            uint seen = sample_view(k, i, node.escape, below);
            all_visible = all_visible && seen == kSeenVisible;
            any_visible = any_visible || seen == kSeenVisible;
            any_blocked = any_blocked || seen == kSeenBlocked;
        }
        bool discard_node = any_blocked && !any_visible && !below;
        bool mixed = (node.flags & kNodeMixedTypes) != 0u;
        if (!leaf && (below || mixed)) {
            refine = true;
        } else if (!leaf && !discard_node) {
            refine = cluster_error_bound(node, p) > tau;
        }
        if (!refine) {
            waiting = true;
            resume = node.escape;
            if (cut.size >= kReconstructionMaxCut) {
                cut.over = true;
                resume = kEndOfWalk;
            } else {
                if (!discard_node) {
                    vec3 contribution = reconstructed_radiance(i, node, p, !all_visible || below, tau);
                    cut.radiance += contribution;
                    tally_indirect(cut.indirect, node.flags, leaf, contribution);
                }
                cut.size += 1u;
                cut.hash += cut_hash_term(uint(i));
            }
        }
    }
    i = subgroupAny(refine) ? node.first_child : node.escape;
}

// The pixel's reconstruction cut; false when the device's loop limit cut the
// walk or one of its rays short, or the cut exceeded max-cut.
bool reconstruction_walk(float tau, SurfacePoint p, out ReconstructionCut cut) {
    cut = ReconstructionCut(vec3(0.0), 0u, 0u, false, no_indirect_sums());
    int i = frame.node_count > 0u ? 0 : kEndOfWalk;
    bool waiting = false;
    int resume = kEndOfWalk;
    g_shadow_walk_cut_short = false;
    for (uint step = 0u; i != kEndOfWalk && step < frame.node_count; step += kWalkUnroll) {
        reconstruction_step(i, waiting, resume, cut, tau, p);
        reconstruction_step(i, waiting, resume, cut, tau, p);
    }
    return i == kEndOfWalk && !g_shadow_walk_cut_short && !cut.over;
}

#endif
