// Per-pixel representatives (render --representatives pixel; Yuksel 2019,
// Lin and Yuksel 2020): a cluster is evaluated through a leaf drawn for the
// pixel, not the one the builder drew for the whole image. From node C the
// draw descends to the first child with probability I_first / (I_first +
// I_second) (scalar intensity: the sum of RGB, as the builder's rule), the
// uniform a hash of the pixel's key and the node's index; the leaf reached is
// the pixel's representative of C. So each leaf is drawn with probability
// I_leaf / I_C, as the builder's representative is, but the draws of two
// pixels are independent; and a parent's representative is always that of
// the child chosen at the parent. Written once, in float on both sides, so
// the CPU evaluator and the shaders take the same branch: the shaders include
// it as GLSL, cpu_evaluator.cpp as C++ in lc::device.
#ifndef LC_DEVICE_PIXEL_REPRESENTATIVE_GLSL_H
#define LC_DEVICE_PIXEL_REPRESENTATIVE_GLSL_H

#include "lightcuts/device/cut_hash.glsl.h"
#include "lightcuts/device/glsl_compat.h"
#include "lightcuts/device/real_math.glsl.h"

#ifdef __cplusplus
namespace lc::device {
#endif

// How clusters are evaluated (Representatives in cpu_evaluator.h; the
// shaders' kSpecRepresentatives).
LC_CONST uint kRepresentativesTree = 0u;
LC_CONST uint kRepresentativesPixel = 1u;
LC_CONST uint kRepresentativesImportance = 2u;

// The pixel's key: every draw of the pixel starts from it. `seed` draws a
// different set of representatives for the same image. The mixer is the cut
// hash's (murmur3's finaliser): every output bit flips with probability
// close to 1/2 for any input bit flipped.
LC_INLINE uint pixel_representative_key(uint x, uint y, uint seed) {
    return cut_hash_term(cut_hash_term(cut_hash_term(seed) ^ x) ^ y);
}

// The pixel's uniform in [0, 1) at a node, exact in float: 24 bits.
LC_INLINE float representative_uniform(uint key, uint node_index) {
    return float(cut_hash_term(key ^ cut_hash_term(node_index)) >> 8u) * (1.0f / 16777216.0f);
}

// The builder's scalar intensity (the sum of RGB), in float.
LC_INLINE float representative_scalar(vec3 I) {
    return I.x + I.y + I.z;
}

// Whether the pixel's draw at a node with two children goes to the first
// (left) one, the children weighing w_first and w_second. A zero or
// non-finite total keeps the first, as the builder does.
LC_INLINE bool pixel_takes_first(uint key, uint node_index, float w_first, float w_second) {
    float sum = w_first + w_second;
    if (!(sum > 0.0f) || !(sum < 3.402823466e38f)) return true;
    return representative_uniform(key, node_index) * sum < w_first;
}

// The draw in proportion to intensity (Representatives::kPixel).
LC_INLINE bool pixel_takes_first_child(uint key, uint node_index, vec3 I_first, vec3 I_second) {
    return pixel_takes_first(key, node_index, representative_scalar(I_first),
                             representative_scalar(I_second));
}

// Representatives::kImportance weighs a child by its scalar intensity times
// g, a cheap upper bound of cos / d^2 over its box of positions at the point
// x with unit normal n: d the distance to the box (kept above 1 cm), cos
// bounded through the box's largest extent along n. Zero only where no
// light of the child can be in front of the surface, so the draw stays
// unbiased; a parent's g is at least each child's (its box holds theirs), so
// a leaf's probability is at least w_L / w_C and the estimate I_L f_L / P(L)
// stays under I_C g_C x the largest f_r. The bound criterion's own bound
// (cone, glossy lobe) weighs slightly better, at 3x the frame's time on
// llvmpipe (docs/BENCHMARKS.md). Directional lights' boxes hold directions:
// they weigh by intensity alone.
LC_INLINE float importance_geometry(vec3 bbox_min, vec3 bbox_max, vec3 x, vec3 n, bool directional) {
    if (directional) return 1.0f;
    vec3 lo = bbox_min - x;
    vec3 hi = bbox_max - x;
    vec3 nearest = max(lo, min(hi, vec3(0.0f)));
    float d2 = max(dot(nearest, nearest), 1e-4f);
    float z_max = dot(n, 0.5f * (lo + hi)) + dot(abs(n), 0.5f * (hi - lo));
    if (!(z_max > 0.0f)) return 0.0f;
    return min(1.0f, z_max / sqrt(d2)) / d2;
}

// The real-time mode's weight: an estimate of cos / d^2 over a child's
// bounding sphere (centre c relative to the point x, radius r) rather than a
// bound. d is the distance to the centre, kept at least r: a child the point
// sits in or beside weighs like its lights on average, not like the nearest
// one (the bound above gives such a box 1e4 and its sibling 1 / d^2, and a
// light drawn from the sibling a weight 1e4 times too large: fireflies). Zero
// only where the whole sphere is behind the surface (dot(n, c) + r <= 0), so
// the draw stays unbiased. The shader's descent reads c and r from
// GpuDrawPair records (lightcuts/tree/draw_pairs.h).
LC_INLINE float stochastic_sphere_geometry(vec3 c, float r, vec3 n) {
    float z_max = dot(n, c) + r;
    if (!(z_max > 0.0f)) return 0.0f;
    float d2 = max(max(dot(c, c), r * r), 1e-4f);
    return min(1.0f, z_max / sqrt(d2)) / d2;
}

LC_INLINE float importance_weight(vec3 I, float geometry) {
    return representative_scalar(I) * geometry;
}

#ifdef __cplusplus
}  // namespace lc::device
#endif

#endif
