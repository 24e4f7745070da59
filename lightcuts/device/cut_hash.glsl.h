// Order-independent identity of a cut: the sum (mod 2^32) of cut_hash_term(i)
// over its node indices. Written once: the shaders include it as GLSL,
// cpu_evaluator.cpp as C++ in lc::device.
#ifndef LC_DEVICE_CUT_HASH_GLSL_H
#define LC_DEVICE_CUT_HASH_GLSL_H

#include "lightcuts/device/real_math.glsl.h"

#ifdef __cplusplus
namespace lc::device {
#endif

// murmur3's fmix32 finaliser of i + 1 (so node 0 does not hash to 0).
LC_INLINE uint cut_hash_term(uint node_index) {
    uint h = node_index + 1u;
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

#ifdef __cplusplus
}  // namespace lc::device
#endif

#endif
