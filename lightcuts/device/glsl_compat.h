// The C/GLSL common subset the CPU/GPU interface is written in: this header
// makes the GLSL spellings (vec3, uint, const) mean the same in C++, so the
// structs, bindings and constants under lightcuts/device/ are written once and
// included by the C++ code and by every shader (glslang -I<source root>).
// tests/shader_interface_test.cpp reflects the compiled SPIR-V against them.
#ifndef LC_DEVICE_GLSL_COMPAT_H
#define LC_DEVICE_GLSL_COMPAT_H

#ifdef __cplusplus
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>

namespace lc {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
}  // namespace lc

#define LC_DEVICE_BEGIN namespace lc {
#define LC_DEVICE_END }
#define LC_CONST inline constexpr
// std430 aligns a struct holding a vec3 to 16 bytes; glm's vec3 aligns to 4.
#define LC_ALIGN16 alignas(16)
// C++ gets the default value; GLSL struct members take none.
#define LC_DEFAULT(value) = value
#else
#define LC_DEVICE_BEGIN
#define LC_DEVICE_END
#define LC_CONST const
#define LC_ALIGN16
#define LC_DEFAULT(value)
#endif

#endif
