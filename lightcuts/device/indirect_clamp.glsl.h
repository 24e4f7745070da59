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
// summed; every light in that sum is at most the second's largest channel, m.
// The sum is scaled by min(1, t / m), which holds each of its lights under t
// too. The clamp is exact while at most two indirect lights exceed t, and
// never lets one exceed it (with more, the smaller ones are clamped a little
// more than they need).
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
    real3 clusters;  // indirect clusters: not clamped, counted in the statistics
    uint leaves;     // indirect leaves added
};

LC_INLINE IndirectSums no_indirect_sums() {
    return IndirectSums(real3(0.0), real3(0.0), real3(0.0), real3(0.0), 0u);
}

LC_INLINE real largest_channel(real3 v) { return max(v.x, max(v.y, v.z)); }

// Keeps the two largest apart: whatever drops out of them joins the rest,
// so every light in the rest stays at most the second's largest channel.
LC_INLINE void place_indirect_leaf(LC_INOUT(IndirectSums) s, real3 contribution) {
    real m = largest_channel(contribution);
    if (m > largest_channel(s.largest)) {
        s.rest += s.second;
        s.second = s.largest;
        s.largest = contribution;
    } else if (m > largest_channel(s.second)) {
        s.rest += s.second;
        s.second = contribution;
    } else {
        s.rest += contribution;
    }
}

LC_INLINE void add_indirect_leaf(LC_INOUT(IndirectSums) s, real3 contribution) {
    place_indirect_leaf(s, contribution);
    s.leaves += 1u;
}

// Adds another part's sums (reference mode splits the leaves over parts).
LC_INLINE void merge_indirect_sums(LC_INOUT(IndirectSums) s, LC_IN(IndirectSums) other) {
    place_indirect_leaf(s, other.largest);
    place_indirect_leaf(s, other.second);
    s.rest += other.rest;
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

// What the clamp removes from a pixel whose unclamped radiance is `total`
// (its cut, classic lights and emission), per channel. Zero when no indirect
// light reaches the threshold, so the pixel is then exactly its total.
LC_INLINE real3 indirect_clamp_removed(real3 total, LC_IN(IndirectSums) s, real ratio) {
    real3 others = max(total - s.largest - s.second - s.rest, real3(0.0));
    real m = largest_channel(s.second);
    real3 removed = real3(0.0);
    for (int c = 0; c < 3; ++c) {
        real t = indirect_clamp_threshold(others[c], s.largest[c], s.second[c], s.rest[c], m, ratio);
        removed[c] = indirect_clamp_excess(s.largest[c], s.second[c], s.rest[c], m, t);
    }
    return removed;
}

#ifdef __cplusplus
}  // namespace lc::device
#endif

#endif
