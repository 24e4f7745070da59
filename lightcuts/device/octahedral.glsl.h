// A unit vector's octahedral decoding (2 x snorm16 in 32 bits, GLSL's
// packSnorm2x16 layout), written once: the shaders include it as GLSL (float,
// shaders/cluster_bounds.glsl), lightcuts/tree/compact_node.cpp as C++
// (double) in lc::octahedral, so the CPU evaluator reads a cone's axis as the
// shaders do. Encoding is the C++'s alone (compact_node.cpp): no shader packs one.
#ifndef LC_DEVICE_OCTAHEDRAL_GLSL_H
#define LC_DEVICE_OCTAHEDRAL_GLSL_H

#include "lightcuts/device/real_math.glsl.h"

#ifdef __cplusplus
#include <algorithm>

namespace lc::octahedral {
using namespace lc::device;
// GLSL's unpackSnorm2x16, in double: each 16-bit half a signed fraction of 32767.
inline real2 unpackSnorm2x16(uint bits) {
    const auto half = [](uint b) { return std::clamp(real(int16_t(uint16_t(b))) / 32767.0, -1.0, 1.0); };
    return real2(half(bits & 0xffffu), half(bits >> 16));
}
#endif

// +1 or -1, never 0: the octahedron's lower half folds outwards from the axes too.
LC_INLINE real sign_not_zero(real v) { return v < 0.0 ? -1.0 : 1.0; }

// The unit vector `bits` encodes: the octahedron's upper half is the square
// itself, the lower half folded over its diagonals.
LC_INLINE real3 decode_octahedral(uint bits) {
    real2 e = unpackSnorm2x16(bits);
    real3 v = real3(e.x, e.y, 1.0 - abs(e.x) - abs(e.y));
    if (v.z < 0.0) {
        v.x = (1.0 - abs(e.y)) * sign_not_zero(e.x);
        v.y = (1.0 - abs(e.x)) * sign_not_zero(e.y);
    }
    return normalize(v);
}

#ifdef __cplusplus
}  // namespace lc::octahedral
#endif

#endif
