// The paper's automatic clamping of indirect light (Sec. 5, "Indirect
// illumination"), written once for the shaders and the CPU evaluator.
//
// A virtual light close to a surface (a VPL near a corner) gives a spike that
// no other light averages out. Each indirect light on the cut (a leaf whose
// light is indirect; clusters are left to the cut's refinement, as in the
// paper) contributes at most ratio x the pixel's total, per channel, with
// ratio = half the error ratio (1% at E = 0.02). The total is the clamped one:
// the threshold t solves t = ratio x (others + sum_i min(L_i, t)), so a pixel
// lit by one spike ends at others / (1 - ratio), not at the spike.
//
// The cut is not kept (the walks evaluate it as they go), so the two largest
// indirect leaves (by their largest channel) are kept apart and the others
// summed with the largest channel among them, m. The sum is scaled by
// min(1, t / m), which holds each of its lights under t too. The clamp is
// exact while at most two indirect lights exceed t, and never lets one exceed
// it (with more, the smaller ones are clamped a little more than they need).
// The rest of the cut is summed apart too: a spike a million times the pixel
// would leave nothing of it in a difference of floats.
//
// The cut's stopping rule (error ratio x the total) reads the clamped total,
// so that a spike does not coarsen the cut of the light around it.
//
// Radiosity patches are indirect but not clamped: a patch is a large emitter
// whose disk falloff (shading.glsl.h) cannot spike, and clamping it as a
// point took a quarter of the radiosity Cornell box's light. Their leaves
// count with the clusters: in the statistics, not in the clamp.
#ifndef LC_DEVICE_INDIRECT_CLAMP_GLSL_H
#define LC_DEVICE_INDIRECT_CLAMP_GLSL_H

#include "lightcuts/device/real_math.glsl.h"

#ifdef __cplusplus
namespace lc::device {
#endif

// One pixel's indirect light on its cut, before the clamp.
struct IndirectSums {
    real3 largest;   // the indirect leaf with the largest channel
    real3 second;    // the next one
    real3 rest;      // the other indirect leaves
    real rest_max;   // the largest channel of a light in rest
    real3 others;    // the rest of the cut: direct light, indirect clusters and patches
    real3 clusters;  // indirect clusters and patches: not clamped, counted in the statistics
    uint leaves;     // indirect leaves added
};

// Field by field: C++ compilers before parenthesised aggregates take no GLSL constructor.
LC_INLINE IndirectSums no_indirect_sums() {
    IndirectSums s;
    s.largest = real3(0.0);
    s.second = real3(0.0);
    s.rest = real3(0.0);
    s.rest_max = 0.0;
    s.others = real3(0.0);
    s.clusters = real3(0.0);
    s.leaves = 0u;
    return s;
}

LC_INLINE real largest_channel(real3 v) { return max(v.x, max(v.y, v.z)); }

// Keeps the two largest apart: whatever drops out of them joins the rest,
// so every light in the rest stays at most the second's largest channel.
LC_INLINE void put_to_rest(LC_INOUT(IndirectSums) s, real3 contribution) {
    s.rest += contribution;
    s.rest_max = max(s.rest_max, largest_channel(contribution));
}

LC_INLINE void place_indirect_leaf(LC_INOUT(IndirectSums) s, real3 contribution) {
    real m = largest_channel(contribution);
    if (m > largest_channel(s.largest)) {
        put_to_rest(s, s.second);
        s.second = s.largest;
        s.largest = contribution;
    } else if (m > largest_channel(s.second)) {
        put_to_rest(s, s.second);
        s.second = contribution;
    } else {
        put_to_rest(s, contribution);
    }
}

LC_INLINE void add_indirect_leaf(LC_INOUT(IndirectSums) s, real3 contribution) {
    place_indirect_leaf(s, contribution);
    s.leaves += 1u;
}

// Whether a node of the cut is clamped: an indirect leaf that is no patch.
LC_INLINE bool clamped_leaf(bool indirect, bool is_patch, bool leaf) {
    return indirect && leaf && !is_patch;
}

// One node of the cut: a clamped leaf (clamped_leaf()) goes to the clamp,
// anything else is the rest.
LC_INLINE void add_cut_node(LC_INOUT(IndirectSums) s, bool indirect, bool clamped, real3 contribution) {
    if (clamped) {
        add_indirect_leaf(s, contribution);
        return;
    }
    s.others += contribution;
    if (indirect) s.clusters += contribution;
}

// Adds another part's sums (reference mode splits the leaves over parts).
LC_INLINE void merge_indirect_sums(LC_INOUT(IndirectSums) s, LC_IN(IndirectSums) other) {
    place_indirect_leaf(s, other.largest);
    place_indirect_leaf(s, other.second);
    s.rest += other.rest;
    s.rest_max = max(s.rest_max, other.rest_max);
    s.others += other.others;
    s.clusters += other.clusters;
    s.leaves += other.leaves;
}

// The threshold of one channel: the largest t with
//   t = ratio x (others + min(a, t) + min(b, t) + rest x min(1, t / m)).
// The right side is concave and piecewise linear in t with breaks at a, b
// and m, so Newton's steps from the unclamped total come down to it without
// overshooting, one piece a step: four steps reach it.
LC_INLINE real indirect_clamp_threshold(real others, real a, real b, real rest, real m, real ratio) {
    real t = ratio * (others + a + b + rest);
    for (int step = 0; step < 4; ++step) {
        real constant = others;
        real slope = 0.0;
        if (a > t) slope += 1.0; else constant += a;
        if (b > t) slope += 1.0; else constant += b;
        if (m > t) slope += rest / m; else constant += rest;
        real denominator = 1.0 - ratio * slope;
        if (!(denominator > 0.0)) break;
        t = min(t, ratio * constant / denominator);
    }
    return t;
}

// What the clamp removes from one channel at threshold t.
LC_INLINE real indirect_clamp_excess(real a, real b, real rest, real m, real t) {
    real excess = max(a - t, 0.0) + max(b - t, 0.0);
    if (m > t) excess += rest * (1.0 - t / m);
    return excess;
}

// The cut's radiance with its indirect leaves clamped, from `total`, the
// cut's unclamped radiance, and its sums; `removed`: what the clamp took, per
// channel. A channel the clamp leaves alone is exactly its total.
LC_INLINE real3 indirect_clamped(real3 total, LC_IN(IndirectSums) s, real ratio, LC_OUT(real3) removed) {
    real3 clamped = total;
    removed = real3(0.0);
    for (int c = 0; c < 3; ++c) {
        real a = s.largest[c];
        real b = s.second[c];
        real t = indirect_clamp_threshold(s.others[c], a, b, s.rest[c], s.rest_max, ratio);
        removed[c] = indirect_clamp_excess(a, b, s.rest[c], s.rest_max, t);
        if (removed[c] > 0.0) {
            real rest_scale = s.rest_max > t ? t / s.rest_max : 1.0;
            clamped[c] = s.others[c] + min(a, t) + min(b, t) + s.rest[c] * rest_scale;
        }
    }
    return clamped;
}

// The clamped total of a cut whose sums hold only its indirect leaves (the
// heap searches, whose other nodes come and go): the rest is total minus them.
LC_INLINE real3 clamped_running_total(real3 total, IndirectSums s, real ratio) {
    s.others = max(total - s.largest - s.second - s.rest, real3(0.0));
    real3 removed;
    return indirect_clamped(total, s, ratio, removed);
}

// ---- The exact clamp (reference mode) ----
// The reference holds every VPL as a leaf, where the approximation above
// over-clamps: with no other light on the pixel it keeps only t = 0 unless
// rest / m > 1 / ratio - 2, and zeroes bounced light that the exact clamp
// keeps. The reference solves t = ratio x (others + sum_i min(L_i, t))
// itself, over passes over its leaves (shaders/reference.comp): the first
// sums them as above; each further one takes the pixel's threshold t and
// tallies per channel the lights at most t (summed: `below`) and those
// above it (counted: `above`). The right side is concave and piecewise
// linear in t, so Newton's step from above,
//   t' = ratio x (others + below) / (1 - ratio x above),
// never goes under the largest root and lands on it from the root's piece;
// no difference of large sums is taken, so a spike loses nothing.

// Newton's passes after the sums (each one a pass over the leaves).
LC_CONST uint kExactClampPasses = 6u;

// Where Newton starts: the largest root with the two largest lights clamped
// and the rest not, above the exact one (clamping the rest only lowers the
// right side).
LC_INLINE real exact_clamp_start(real others, real a, real b, real rest, real ratio) {
    return indirect_clamp_threshold(others, a, b, rest, 0.0, ratio);
}

// One light of a pass at the pixel's threshold t, per channel.
LC_INLINE void tally_exact_clamp(LC_INOUT(real3) below, LC_INOUT(real3) above, real3 contribution, real3 t) {
    for (int c = 0; c < 3; ++c) {
        if (contribution[c] > t[c]) {
            above[c] += 1.0;
        } else {
            below[c] += contribution[c];
        }
    }
}

// Newton's step from t (at or above the root) with the pass's tally at t.
LC_INLINE real exact_clamp_step(real others, real below, real above, real t, real ratio) {
    real denominator = 1.0 - ratio * above;
    if (!(denominator > 0.0)) return t;
    return min(t, ratio * (others + below) / denominator);
}

#ifdef __cplusplus
}  // namespace lc::device
#endif

#endif
