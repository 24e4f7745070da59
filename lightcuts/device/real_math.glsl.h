// The C/GLSL common subset in which a formula is written once for both the
// shaders and the CPU evaluator (docs/CODE_STYLE.md). A header that includes
// this one compiles as GLSL (glslang, -I of the project root) and as C++:
//   real, real2, real3: float, vec2, vec3 in GLSL; double, glm::dvec2, glm::dvec3 in C++ (the CPU
//     evaluator is the double-precision ground truth);
//   GLSL's built-ins (abs, clamp, dot, length, normalize, max, min, acos, exp2,
//     pow, sqrt) come from glm and <cmath> under the same names in lc::device;
//   LC_INLINE, LC_CONST, LC_IN(T), LC_OUT(T), LC_INOUT(T) spell what differs:
//     inline functions and constants, read-only, out and in-out parameters.
// Write literals as decimals (1.0, not 1): GLSL converts neither way.
#ifndef LC_DEVICE_REAL_MATH_GLSL_H
#define LC_DEVICE_REAL_MATH_GLSL_H

#ifdef __cplusplus

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>

namespace lc::device {

using real = double;
using real2 = glm::dvec2;
using real3 = glm::dvec3;
using uint = std::uint32_t;

// Scalars and vectors alike: glm's follow GLSL's definitions.
using glm::abs;
using glm::clamp;
using glm::dot;
using glm::length;
using glm::max;
using glm::min;
using glm::normalize;
// Only ever called on scalars here.
using std::acos;
using std::exp2;
using std::pow;
using std::sqrt;

// Some constants are about rounding and so depend on the precision.
// A few ulps of real, relative.
inline constexpr real kFewUlps = 1e-15;

// copysign(1, x): the sign bit decides, so -0 gives -1.
inline real copysign_one(real x) { return std::copysign(1.0, x); }

}  // namespace lc::device

#define LC_INLINE inline
#define LC_CONST inline constexpr
#define LC_IN(T) const T&
#define LC_OUT(T) T&
#define LC_INOUT(T) T&

#else  // GLSL

#define real float
#define real2 vec2
#define real3 vec3
#define LC_INLINE
#define LC_CONST const
#define LC_IN(T) T
#define LC_OUT(T) out T
#define LC_INOUT(T) inout T

const float kFewUlps = 1e-6;

float copysign_one(float x) {
    return uintBitsToFloat((floatBitsToUint(x) & 0x80000000u) | floatBitsToUint(1.0));
}

#endif

#endif
