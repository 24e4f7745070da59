#version 460
// The real-time mode's lighting (Lin and Yuksel 2020, Real-Time Stochastic
// Lightcuts): each workgroup is a block of pixels that shares one cut of the
// light tree, refined at a pivot pixel drawn anew every frame, at most
// kStochasticCut nodes. Every pixel then draws one light inside each cut node,
// descending the node's subtree with probabilities from the children's
// importance at the pixel (stochastic_draw.glsl, one GpuDrawPair a level),
// and shades it with its intensity over its probability and one shadow ray:
// an unbiased estimate of the tree's light with at most kStochasticCut shadow
// rays per pixel, whatever the number of lights; or, under a smaller budget,
// kStochasticRays rays picked among the drawn lights (shadow_ray_budget.glsl).
// The temporal pass averages the frames.
#extension GL_GOOGLE_include_directive : require

#include "bound_criterion.glsl"
#include "stochastic_draw.glsl"
#include "shadow_ray_budget.glsl"

layout(constant_id = kSpecStochasticCut) const uint kStochasticCut = 16u;

shared int s_cut_node[kMaxStochasticCut];
shared float s_cut_bound[kMaxStochasticCut];
shared uint s_cut_size;
shared bool s_has_surface[kMaxWorkgroupInvocations];

// How much refining node i at the pivot could change the estimate: 0 for a
// leaf (nothing to split), +inf for a junction of several light types.
float split_priority(int i, SurfacePoint p) {
    GpuTreeNode node = tree_nodes[i];
    if (node.first_child == kNoChild) return 0.0;
    if ((node.flags & kNodeMixedTypes) != 0u) return uintBitsToFloat(0x7f800000u);
    return cluster_error_bound(node, p);
}

void append_cut_node(int i, SurfacePoint p) {
    if (left_out(tree_nodes[i].flags)) return;
    s_cut_node[s_cut_size] = i;
    s_cut_bound[s_cut_size] = split_priority(i, p);
    ++s_cut_size;
}

// The entry with the largest split priority (the first of equals), -1 when no
// entry can be split.
int largest_entry() {
    int best = -1;
    float best_bound = 0.0;
    for (uint k = 0u; k < s_cut_size; ++k) {
        if (s_cut_bound[k] > best_bound) {
            best = int(k);
            best_bound = s_cut_bound[k];
        }
    }
    return best;
}

// The block's cut, refined at the pivot like the paper's heap (largest bound
// first) until it holds kStochasticCut nodes or only leaves. One invocation
// writes it into shared memory; at most kStochasticCut - 1 splits of at most
// kStochasticCut entries each, so no loop nears a device's limit.
void refine_block_cut(SurfacePoint pivot) {
    s_cut_size = 0u;
    if (frame.node_count == 0u) return;
    append_cut_node(0, pivot);
    for (uint step = 0u; step + 1u < kStochasticCut; ++step) {
        int k = largest_entry();
        if (k < 0) break;
        int parent = s_cut_node[k];
        int c0 = tree_nodes[parent].first_child;
        int c1 = tree_nodes[c0].escape;
        bool two = c1 != kEndOfWalk && c1 != tree_nodes[parent].escape;
        // The parent's slot goes to the last entry; the children are appended.
        --s_cut_size;
        s_cut_node[k] = s_cut_node[s_cut_size];
        s_cut_bound[k] = s_cut_bound[s_cut_size];
        append_cut_node(c0, pivot);
        if (two) append_cut_node(c1, pivot);
    }
}

// The block's pivot: the first pixel with geometry from a place drawn for this
// block and frame, -1 when the block shows only background.
int block_pivot() {
    uint count = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
    uint block = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint start = cut_hash_term(cut_hash_term(frame.frame_seed) ^ block) % count;
    for (uint k = 0u; k < count; ++k) {
        uint i = (start + k) % count;
        if (s_has_surface[i]) return int(i);
    }
    return -1;
}

// A drawn light's radiance at p, with its shadow ray. In uniform control
// flow (the shadow walk is the subgroup's); `shaded` false adds nothing.
vec3 drawn_light_radiance(GpuLight light, SurfacePoint p, bool shaded) {
    vec3 l;
    vec3 e = shaded ? light_irradiance(light, p.position, p.normal, l) : vec3(0.0);
    if (kShadows) e *= light_visibility(light, p.position, p.normal, max_channel(e) > 0.0);
    return shaded ? brdf_toward(p, l) * e : vec3(0.0);
}

void add_to_cut(inout Cut cut, int i, GpuTreeNode node, vec3 contribution) {
    cut.radiance += contribution;
    tally_indirect(cut.indirect, node.flags, node.first_child == kNoChild, contribution);
    cut.hash += cut_hash_term(uint(i));
}

// The cut's k-th node (tree node i), its light drawn: shaded with its own
// shadow ray, or, under the budget, unshadowed and offered to the picks. The
// budget's branch is the workgroup's, so uniform.
void shade_cut_node(inout Cut cut, inout ShadowBudget budget, bool budgeted, uint k, int i, GpuTreeNode node,
                    Descent d, SurfacePoint p, bool surface) {
    GpuLight light = finish_descent(d, node);
    if (!budgeted) {
        add_to_cut(cut, i, node, drawn_light_radiance(light, p, surface));
        return;
    }
    vec3 l;
    vec3 e = surface ? light_irradiance(light, p.position, p.normal, l) : vec3(0.0);
    vec3 unshadowed = surface ? brdf_toward(p, l) * e : vec3(0.0);
    offer_to_budget(budget, k, drawn_light_index(d, node), unshadowed, node.flags, node.first_child == kNoChild);
    cut.hash += cut_hash_term(uint(i));
}

// Every cut node's drawn light at p, two descents at a time. The number of
// nodes is the workgroup's, so the branch on a second one is uniform.
Cut shade_block_cut(SurfacePoint p, bool surface) {
    Cut cut = empty_cut();
    bool budgeted = shadow_budget_applies(s_cut_size);
    ShadowBudget budget = empty_shadow_budget();
    for (uint k = 0u; k < s_cut_size; k += 2u) {
        bool second = k + 1u < s_cut_size;
        int i0 = s_cut_node[k];
        int i1 = s_cut_node[second ? k + 1u : k];
        GpuTreeNode node0 = tree_nodes[i0];
        GpuTreeNode node1 = tree_nodes[i1];
        Descent d0 = start_descent(i0, node0);
        Descent d1 = second ? start_descent(i1, node1) : Descent(-1, 1.0, start_chain(0.0));
        descend_both(d0, d1, p);
        shade_cut_node(cut, budget, budgeted, k, i0, node0, d0, p, surface);
        if (second) shade_cut_node(cut, budget, budgeted, k + 1u, i1, node1, d1, p, surface);
    }
    if (budgeted) resolve_shadow_budget(budget, p, cut);
    cut.size = s_cut_size;
    return cut;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = pixel.x < int(frame.width) && pixel.y < int(frame.height);
    SurfacePoint p;
    // Lanes off the image still walk the shared shadow rays: they shade pixel
    // (0, 0)'s point, and add nothing.
    bool surface = load_surface(inside ? pixel : ivec2(0), p) && inside;
    s_has_surface[gl_LocalInvocationIndex] = surface;
    barrier();
    int pivot = block_pivot();
    if (int(gl_LocalInvocationIndex) == pivot) refine_block_cut(p);
    barrier();
    if (pivot < 0) {
        if (inside) store_background(pixel);
        return;  // the whole workgroup: no barrier follows
    }
    g_pixel_key = pixel_representative_key(uint(pixel.x), uint(pixel.y), frame.frame_seed);
    set_frame_strata(pixel, frame.draw_seed, frame.frame_number);
    Cut cut = shade_block_cut(p, surface);
    if (!inside) return;
    if (!surface) {
        store_background(pixel);
        return;
    }
    vec3 radiance = clamp_indirect(pixel, cut.radiance, cut.indirect) + classic_and_emitted_radiance(p);
    store_pixel(pixel, radiance, cut.size, cut.hash, false);
}
