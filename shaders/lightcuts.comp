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
//   bound, walk search (the default; editor_client/render/bound_walk.h):
//     threshold passes, each a pre-order walk shared by the subgroup like the
//     radius walk, refining every node whose error bound exceeds the pass's
//     threshold; passes stop once every bound on the cut is <= error x the
//     cut's total, the cut would exceed max-cut (the pixel keeps the previous
//     pass's cut and counts in counters.max_cut_hits) or the passes run out.
//     A pass that llvmpipe's loop limit cuts short runs again in the next
//     dispatch, the search kept per pixel in walk_states between them.
//     Mirrors bound_walk_cut() in bound_walk.cpp.
//   bound, heap search (the paper's order, Sec. 4): a max-heap of (bound, node, unit response)
//     entries in private memory, at most max-cut of them (a specialization
//     constant, so the array is sized at pipeline creation). The node with the
//     largest error bound is refined until every bound is <= error x the total
//     estimate, or the cut holds max-cut nodes (the pixel is then counted in
//     counters.max_cut_hits). Mirrors bound_cut() in cpu_evaluator.cpp,
//     including its tie order and the largest-channel comparisons.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require

#include "cut_hash.glsl"
#include "cluster_bounds.glsl"
#include "lighting_pass.glsl"
#include "lightcuts/device/walk_schedule.glsl.h"

layout(local_size_x_id = 0, local_size_y_id = 1) in;

const uint kCriterionRadius = 0u;
const uint kCriterionBound = 1u;
layout(constant_id = 8) const uint kCriterion = kCriterionRadius;
layout(constant_id = 11) const float kErrorRatio = 0.02;
// Heap capacity = the max-cut setting (at least 2 so one refinement fits);
// 2 under the walk search, which keeps no heap.
layout(constant_id = 12) const int kMaxCut = 2;
const uint kBoundSearchWalk = 0u;
const uint kBoundSearchHeap = 1u;
layout(constant_id = 13) const uint kBoundSearch = kBoundSearchWalk;
// The walk search's max-cut and pass schedule (bound_walk.h).
layout(constant_id = 14) const uint kWalkMaxCut = 1000u;
layout(constant_id = 15) const uint kWalkMaxPasses = 12u;
layout(constant_id = 16) const float kWalkShrink = 512.0;
layout(constant_id = 17) const float kWalkMargin = 0.8;
layout(constant_id = 18) const uint kWalkBisections = 6u;

struct Cut {
    vec3 radiance;  // sum over cut nodes of f_r * I_C * color * G * V
    uint size;
    uint hash;
};

void add_to_cut(inout Cut cut, uint node_index, GpuLight cluster, SurfacePoint p) {
    cut.radiance += light_radiance(cluster, p);
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
// One step of the walk. Written as a function and called kRadiusUnroll times per
// loop iteration: llvmpipe limits the loop iterations of an invocation
// (loop_limits.glsl), not the straight-line steps inside one.
void radius_walk_step(inout int i, inout bool waiting, inout int resume, inout Cut cut, SurfacePoint p) {
    if (i == kEndOfWalk) return;  // i is the same on every lane of the subgroup
    if (waiting && i == resume) waiting = false;
    bool refine = !waiting && refine_by_radius(i, p.position);
    if (!waiting && !refine) {
        add_to_cut(cut, uint(i), tree_nodes[i].light, p);
        waiting = true;
        resume = tree_nodes[i].escape;
    }
    i = subgroupAny(refine) ? tree_nodes[i].first_child : tree_nodes[i].escape;
}

// `cut_short`: the walk did not reach its end (the device's loop limit).
Cut select_cut_radius(SurfacePoint p, out bool cut_short) {
    Cut cut = Cut(vec3(0.0), 0u, 0u);
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

// ---- bound criterion -------------------------------------------------------

float heap_key[kMaxCut];
int heap_node[kMaxCut];
vec3 heap_unit[kMaxCut];  // f_r * G of the representative per unit intensity

float max_channel(vec3 v) { return max(v.x, max(v.y, v.z)); }

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
    if (node.first_child == kEndOfWalk) return 0.0;
    if ((node.flags & kNodeMixedTypes) != 0u) return uintBitsToFloat(0x7f800000u);
    return max_channel(response_bound_of(node, node_bounds[i], p) * node.light.intensity);
}

vec3 unit_response(int i, SurfacePoint p) {
    GpuLight unit_light = tree_nodes[i].light;
    unit_light.intensity = vec3(1.0);
    return light_radiance(unit_light, p);
}

// A child whose representative has the parent's parameters has the parent's
// response: the evaluation is reused (paper Sec. 4.1).
bool same_emitter(GpuLight a, GpuLight b) {
    return a.position == b.position && a.direction == b.direction && a.type == b.type &&
           a.range == b.range && a.spot_cos_outer == b.spot_cos_outer &&
           a.spot_scale == b.spot_scale;
}

// Returns the outgoing radiance of the cut (f_r already applied) in `radiance`.
Cut select_cut_bound(SurfacePoint p, out vec3 radiance, out bool max_cut_hit) {
    max_cut_hit = false;
    radiance = vec3(0.0);
    Cut cut = Cut(vec3(0.0), 0u, 0u);
    if (frame.node_count == 0u) return cut;
    int size = 0;
    vec3 root_unit = unit_response(0, p);
    heap_push(size, node_key(0, p), 0, root_unit);
    vec3 total = root_unit * tree_nodes[0].light.intensity;
    // Each refinement adds one node net; node_count refinements always suffice.
    for (uint step = 0u; step < frame.node_count && size > 0; ++step) {
        float key = heap_key[0];
        if (!isinf(key)) {
            if (!(key > 0.0)) break;
            if (key <= kErrorRatio * max(max_channel(total), 0.0)) break;
        }
        // A mixed-type junction is refined past max-cut like on the CPU, as
        // long as the array has room.
        if ((!isinf(key) && size >= kMaxCut) || size + 1 > kMaxCut) {
            max_cut_hit = true;
            break;
        }
        int parent = heap_node[0];
        vec3 parent_unit = heap_unit[0];
        heap_pop(size);
        GpuLight parent_light = tree_nodes[parent].light;
        total -= parent_unit * parent_light.intensity;
        // Children: first_child, and its escape when that is not the parent's
        // escape (the right sibling of a left child).
        int c0 = tree_nodes[parent].first_child;
        int c1 = tree_nodes[c0].escape;
        bool two = c1 != kEndOfWalk && c1 != tree_nodes[parent].escape;
        for (int c = 0; c < (two ? 2 : 1); ++c) {
            int child = c == 0 ? c0 : c1;
            GpuLight light = tree_nodes[child].light;
            vec3 unit = same_emitter(light, parent_light) ? parent_unit
                                                          : unit_response(child, p);
            total += unit * light.intensity;
            heap_push(size, node_key(child, p), child, unit);
        }
    }
    // The running total drifts; sum afresh.
    for (int k = 0; k < size; ++k) {
        radiance += heap_unit[k] * tree_nodes[heap_node[k]].light.intensity;
        cut.hash += cut_hash_term(uint(heap_node[k]));
    }
    cut.size = uint(size);
    return cut;
}

// ---- bound criterion, walk search ------------------------------------------

// One threshold pass of one lane.
struct WalkPass {
    vec3 radiance;  // f_r already applied
    uint size;
    uint hash;
    float worst;    // largest bound among the cut's non-leaf nodes
    bool over;      // the cut would exceed max-cut: the pass is abandoned
};

// One step of a pass; like radius_walk_step, the subgroup shares the walk and
// a lane that takes a node as a cluster waits for the walk to leave its
// subtree. A lane sitting the pass out (done, or over max-cut) waits for
// kEndOfWalk, which no node index equals.
// `shade` false: only sizes the cut (no light is evaluated, no ray traced).
void bound_walk_step(inout int i, inout bool waiting, inout int resume, inout WalkPass pass,
                     float tau, bool limit_size, bool shade, SurfacePoint p) {
    if (i == kEndOfWalk) return;
    if (waiting && i == resume) waiting = false;
    // One load of the node per step: llvmpipe gathers every field per lane,
    // and loads in different branches are not merged.
    GpuTreeNode node = tree_nodes[i];
    bool refine = false;
    if (!waiting) {
        bool leaf = node.first_child == kEndOfWalk;
        bool mixed = (node.flags & kNodeMixedTypes) != 0u;
        float key = 0.0;
        if (!leaf && !mixed)
            key = max_channel(response_bound_of(node, node_bounds[i], p) * node.light.intensity);
        refine = !leaf && (mixed || key > tau);
        if (!refine) {
            waiting = true;
            if (limit_size && pass.size >= kWalkMaxCut) {
                pass.over = true;
                resume = kEndOfWalk;
            } else {
                if (shade) pass.radiance += light_radiance(node.light, p);
                pass.size += 1u;
                pass.hash += cut_hash_term(uint(i));
                pass.worst = max(pass.worst, key);
                resume = node.escape;
            }
        }
    }
    i = subgroupAny(refine) ? node.first_child : node.escape;
}

// Where pass 0 starts: tau = +inf keeps the per-type roots.
GpuWalkState walk_start() {
    return GpuWalkState(vec3(0.0), 0u, 0u, uintBitsToFloat(0x7f800000u), 0.0, 0.0,
                        kWalkBisections << kWalkBisectionsShift, 0u, 0u, 0u);
}

// The cut at threshold tau (`shade` false: its size, hash and worst bound
// only). False when the walk or a ray of it was cut short.
bool walk_cut(float tau, bool limit_size, bool shade, out WalkPass pass, SurfacePoint p) {
    pass = WalkPass(vec3(0.0), 0u, 0u, 0.0, false);
    int i = frame.node_count > 0u ? 0 : kEndOfWalk;  // an empty tree: an empty cut
    bool waiting = false;
    int resume = kEndOfWalk;
    g_shadow_walk_cut_short = false;
    // Two steps per iteration: the step is large, and more copies spill
    // (measured: 8 copies 1.4x slower).
    for (uint step = 0u; i != kEndOfWalk && step < frame.node_count; step += kWalkUnroll) {
        bound_walk_step(i, waiting, resume, pass, tau, limit_size, shade, p);
        bound_walk_step(i, waiting, resume, pass, tau, limit_size, shade, p);
    }
    return i == kEndOfWalk && !g_shadow_walk_cut_short;
}

// One pass of one lane's search (s.passes numbers it): walks with s.tau,
// then keeps the cut if it fit and sets the next threshold, or marks the
// search done. Returns false, leaving s as it was, when the device's loop
// limit (or a corrupt tree) ended the walk or one of its shadow rays early.
bool walk_pass(inout GpuWalkState s, SurfacePoint p) {
    bool limit_size = s.passes > 0u;
    bool bisecting = (s.flags & kWalkBisecting) != 0u;
    WalkPass pass;
    // With shadow rays, a pass that may well exceed max-cut (bisecting, or
    // the last cut already a quarter of it) is sized first and shaded only
    // if it fits: the same decisions, without tracing the rays of cuts that
    // are thrown away. Sizing costs a walk of bounds; rays cost far more.
    bool size_first =
        kShadows && limit_size && (bisecting || s.size * 4u >= kWalkMaxCut);
    if (size_first && !walk_cut(s.tau, limit_size, false, pass, p)) return false;
    if (!(size_first && pass.over) && !walk_cut(s.tau, limit_size, true, pass, p)) return false;
    ++s.passes;
    if (s.passes >= kWalkMaxPasses) s.flags |= kWalkDone;  // unless the rule is met below
    if (pass.over) {
        s.flags |= kWalkBisecting;
        s.over_lo = s.tau;
    } else {
        s.radiance = pass.radiance;
        s.size = pass.size;
        s.hash = pass.hash;
        float limit = kErrorRatio * max(max_channel(pass.radiance), 0.0);
        if (!(pass.worst > limit)) {
            s.flags |= kWalkDone | kWalkRuleMet;
            return true;
        }
        s.fit_hi = pass.worst;
        if (!bisecting) {
            s.tau = next_walk_threshold(limit, pass.worst, kWalkMargin, kWalkShrink);
            return true;
        }
    }
    // Over max-cut once: bisect between the last fit and the last over.
    uint bisections_left = s.flags >> kWalkBisectionsShift;
    if (bisections_left == 0u) {
        s.flags |= kWalkDone;
        return true;
    }
    s.flags = (s.flags & ((1u << kWalkBisectionsShift) - 1u)) |
              ((bisections_left - 1u) << kWalkBisectionsShift);
    s.tau = bisection_threshold(s.fit_hi, s.over_lo);
    return true;
}

// The walk search over up to kWalkMaxPasses dispatches (Renderer::record;
// frame.walk_dispatch numbers them). Each dispatch runs passes until the pixel's
// search is done or llvmpipe's loop limit (loop_limits.glsl) cuts a pass
// short; the search is then kept in walk_states and the cut-short pass runs
// again, whole, in the next dispatch with a fresh budget. Most pixels finish
// in the first dispatch, so the later ones are nearly empty. Only a pass that
// exceeds the limit on its own (the first of its dispatch) ends the search:
// the pixel keeps its last complete pass and counts in loop_limit_stops. A
// pixel is stored once, when its search ends; later dispatches skip it.
void bound_walk_dispatch(ivec2 pixel) {
    uint index = uint(pixel.y) * frame.width + uint(pixel.x);
    GpuWalkState s;
    if (frame.walk_dispatch == 0u) {
        s = walk_start();
    } else {
        s = walk_states[index];
        if ((s.flags & (kWalkDone | kWalkStorePending)) == kWalkDone) return;
    }
    SurfacePoint p;
    if (!load_surface(pixel, p)) {
        store_background(pixel);
        walk_states[index].flags = kWalkDone;
        return;
    }
    // Every dispatch completes a pass or ends the search, so kWalkMaxPasses
    // dispatches end every search; the last one stores whatever is left.
    bool last_dispatch = frame.walk_dispatch + 1u >= kWalkMaxPasses;
    bool limited = false;
    for (uint run = 0u; (s.flags & kWalkDone) == 0u; ++run) {
        if (!walk_pass(s, p)) {
            limited = true;
            if (run == 0u || last_dispatch) s.flags |= kWalkDone | kWalkLoopStop;
            break;
        }
    }
    if (last_dispatch) s.flags |= kWalkDone;
    g_shadow_walk_cut_short = false;  // in the flags: counted once, when the pixel is stored
    // Storing adds the classic lights, whose loop the spent budget would cut
    // short too: a search that ended where the limit fired is stored next time.
    if ((s.flags & kWalkDone) == 0u || (limited && !last_dispatch)) {
        if (limited && (s.flags & kWalkDone) != 0u) s.flags |= kWalkStorePending;
        walk_states[index] = s;
        flush_shadow_ray_count();
        return;
    }
    walk_states[index].flags = kWalkDone;
    bool loop_limit_stop = (s.flags & kWalkLoopStop) != 0u;
    // Stopped by max-cut, or still refining after the last pass.
    if ((s.flags & kWalkRuleMet) == 0u && !loop_limit_stop) atomicAdd(counters.max_cut_hits, 1u);
    store_pixel(pixel, s.radiance + classic_and_emitted_radiance(p), s.size, s.hash,
                loop_limit_stop);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
    if (kCriterion == kCriterionBound && kBoundSearch == kBoundSearchWalk) {
        bound_walk_dispatch(pixel);
        return;
    }
    SurfacePoint p;
    if (!load_surface(pixel, p)) {
        store_background(pixel);
        return;
    }
    if (kCriterion == kCriterionBound) {
        vec3 radiance;
        bool max_cut_hit;
        Cut cut = select_cut_bound(p, radiance, max_cut_hit);
        if (max_cut_hit) atomicAdd(counters.max_cut_hits, 1u);
        radiance += classic_and_emitted_radiance(p);
        store_pixel(pixel, radiance, cut.size, cut.hash, false);
        return;
    }
    bool walk_cut_short;
    Cut cut = select_cut_radius(p, walk_cut_short);
    store_pixel(pixel, cut.radiance + classic_and_emitted_radiance(p), cut.size, cut.hash,
                walk_cut_short);
}
