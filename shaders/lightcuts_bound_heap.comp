#version 460
// Lightcuts with the bound criterion, heap search (the paper's order, Sec. 4):
// a max-heap of (bound, node, unit response) entries in private memory, at
// most kHeapCapacity of them (a specialization constant, so the array is
// sized at pipeline creation: max-cut, or less where the driver refuses that
// much private memory, as NVIDIA's does 20 KB). The node with the largest
// error bound is refined until every bound is <= error x the total estimate,
// or the cut holds max-cut nodes or fills the heap (the pixel is then counted
// in counters.max_cut_hits). Mirrors bound_cut() in
// cpu_evaluator.cpp, including its tie order and the largest-channel
// comparisons.
#extension GL_GOOGLE_include_directive : require

#include "bound_criterion.glsl"

// The max-cut setting, and the heap's capacity: at most max-cut, at least 2
// so one refinement fits.
layout(constant_id = kSpecMaxCut) const int kMaxCut = 2;
layout(constant_id = kSpecHeapCapacity) const int kHeapCapacity = 2;

float heap_key[kHeapCapacity];
int heap_node[kHeapCapacity];
vec3 heap_unit[kHeapCapacity];  // f_r * G of the representative per unit intensity

// cpu_evaluator's heap_less on (key, node) pairs: larger bound first, then the
// smaller node index.
bool entry_less(float key_a, int node_a, float key_b, int node_b) {
    if (key_a != key_b) return key_a < key_b;
    return node_a > node_b;
}

void heap_store(int i, float key, int node, vec3 unit) {
    heap_key[i] = key;
    heap_node[i] = node;
    heap_unit[i] = unit;
}

void heap_move(int to, int from) { heap_store(to, heap_key[from], heap_node[from], heap_unit[from]); }

// Sifts with a hole instead of swaps: one write per level (scratch memory is
// what a lane pays for on a CPU device).
void heap_push(inout int size, float key, int node, vec3 unit) {
    int i = size++;
    while (i > 0) {
        int parent = (i - 1) / 2;
        if (!entry_less(heap_key[parent], heap_node[parent], key, node)) break;
        heap_move(i, parent);
        i = parent;
    }
    heap_store(i, key, node, unit);
}

// Removes the root: the last entry falls into the hole left at the top.
void heap_pop(inout int size) {
    --size;
    float key = heap_key[size];
    int node = heap_node[size];
    vec3 unit = heap_unit[size];
    int i = 0;
    while (true) {
        int l = 2 * i + 1;
        if (l >= size) break;
        int r = l + 1;
        int child = l;
        if (r < size && entry_less(heap_key[l], heap_node[l], heap_key[r], heap_node[r])) child = r;
        if (!entry_less(key, node, heap_key[child], heap_node[child])) break;
        heap_move(i, child);
        i = child;
    }
    if (size > 0) heap_store(i, key, node, unit);
}

// Error bound of node i (largest channel): 0 for a leaf (exact), +inf for a
// mixed-type junction (always refined), else f_r bound x G bound x I_C.
float node_key(int i, SurfacePoint p) {
    GpuTreeNode node = tree_nodes[i];
    if (node.first_child == kNoChild) return 0.0;
    if ((node.flags & kNodeMixedTypes) != 0u) return uintBitsToFloat(0x7f800000u);
    return cluster_error_bound(node, p);
}

vec3 unit_response(int i, SurfacePoint p) {
    GpuLight unit_light = leaf_lights[pixel_draw(i, tree_nodes[i], p).light];
    unit_light.intensity = vec3(1.0);
    return light_radiance(unit_light, p);
}

// Returns the outgoing radiance of the cut (f_r already applied) in `radiance`.
Cut select_cut_bound(SurfacePoint p, out vec3 radiance, out bool max_cut_hit) {
    max_cut_hit = false;
    radiance = vec3(0.0);
    Cut cut = empty_cut();
    if (frame.node_count == 0u || left_out(tree_nodes[0].flags)) return cut;
    int size = 0;
    vec3 root_unit = unit_response(0, p);
    heap_push(size, node_key(0, p), 0, root_unit);
    vec3 total = root_unit * tree_nodes[0].intensity;
    // Its indirect leaves, for the clamped total the rule reads.
    IndirectSums leaves = no_indirect_sums();
    if (kIndirectClamp && clamped_node(tree_nodes[0].flags, tree_nodes[0].first_child == kNoChild))
        add_indirect_leaf(leaves, total);
    // Each refinement adds one node net; node_count refinements always suffice.
    for (uint step = 0u; step < frame.node_count && size > 0; ++step) {
        float key = heap_key[0];
        if (!isinf(key)) {
            if (!(key > 0.0)) break;
            if (key <= kErrorRatio * max(max_channel(clamped_heap_total(total, leaves)), 0.0)) break;
        }
        // A mixed-type junction is refined past max-cut like on the CPU, as
        // long as the array has room.
        if ((!isinf(key) && size >= kMaxCut) || size + 1 > kHeapCapacity) {
            max_cut_hit = true;
            break;
        }
        int parent = heap_node[0];
        vec3 parent_unit = heap_unit[0];
        heap_pop(size);
        uint parent_representative = tree_nodes[parent].representative;
        total -= parent_unit * tree_nodes[parent].intensity;
        // Children: first_child, and its escape when that is not the parent's
        // escape (the right sibling of a left child).
        int c0 = tree_nodes[parent].first_child;
        int c1 = tree_nodes[c0].escape;
        bool two = c1 != kEndOfWalk && c1 != tree_nodes[parent].escape;
        // With per-pixel representatives the parent's is the one of the child
        // the pixel's draw takes at the parent.
        bool draw_takes_first = kRepresentatives == kRepresentativesPixel &&
            (!two || pixel_takes_first_child(g_pixel_key, uint(parent), tree_nodes[c0].intensity,
                                             tree_nodes[c1].intensity));
        for (int c = 0; c < (two ? 2 : 1); ++c) {
            int child = c == 0 ? c0 : c1;
            // A child with its parent's representative has its parent's
            // response: the evaluation is reused (paper Sec. 4.1).
            GpuTreeNode child_node = tree_nodes[child];
            if (left_out(child_node.flags)) continue;
            bool shares = kRepresentatives == kRepresentativesPixel ? (c == 0) == draw_takes_first
                                                : child_node.representative == parent_representative;
            vec3 unit = shares ? parent_unit : unit_response(child, p);
            total += unit * child_node.intensity;
            if (kIndirectClamp && clamped_node(child_node.flags, child_node.first_child == kNoChild))
                add_indirect_leaf(leaves, unit * child_node.intensity);
            heap_push(size, node_key(child, p), child, unit);
        }
    }
    // The running total drifts; sum afresh.
    for (int k = 0; k < size; ++k) {
        GpuTreeNode node = tree_nodes[heap_node[k]];
        vec3 contribution = heap_unit[k] * node.intensity;
        radiance += contribution;
        tally_indirect(cut.indirect, node.flags, node.first_child == kNoChild, contribution);
        cut.hash += cut_hash_term(uint(heap_node[k]));
    }
    cut.size = uint(size);
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
    set_pixel_representatives(pixel);
    vec3 radiance;
    bool max_cut_hit;
    Cut cut = select_cut_bound(p, radiance, max_cut_hit);
    if (max_cut_hit) atomicAdd(counters.max_cut_hits, 1u);
    radiance = clamp_indirect(pixel, radiance, cut.indirect) + classic_and_emitted_radiance(p);
    store_pixel(pixel, radiance, cut.size, cut.hash, false);
}
