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

#ifdef __cplusplus
namespace lc::device {
#endif

// Chris Wellons' lowbias32: a bijection on 32 bits whose output bits each
// flip with probability close to 1/2 for any input bit flipped.
LC_INLINE uint representative_mix(uint h) {
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

// The pixel's key: every draw of the pixel starts from it. `seed` draws a
// different set of representatives for the same image.
LC_INLINE uint pixel_representative_key(uint x, uint y, uint seed) {
    return representative_mix(representative_mix(representative_mix(seed + 0x9e3779b9u) ^ x) ^ y);
}

// The pixel's uniform in [0, 1) at a node, exact in float: 24 bits.
LC_INLINE float representative_uniform(uint key, uint node_index) {
    return float(representative_mix(key ^ cut_hash_term(node_index)) >> 8u) * (1.0f / 16777216.0f);
}

// Whether the pixel's draw at a node with two children goes to the first
// (left) one. A zero or non-finite total keeps the first, as the builder does.
LC_INLINE bool pixel_takes_first_child(uint key, uint node_index, vec3 I_first, vec3 I_second) {
    float first = I_first.x + I_first.y + I_first.z;
    float sum = first + (I_second.x + I_second.y + I_second.z);
    if (!(sum > 0.0f) || !(sum < 3.402823466e38f)) return true;
    return representative_uniform(key, node_index) * sum < first;
}

#ifdef __cplusplus
}  // namespace lc::device
#endif

#endif
