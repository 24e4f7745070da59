// Push constants of one G-buffer draw (GpuDrawConstants, lightcuts/device/gpu_structs.h).
#ifndef LC_DRAW_CONSTANTS_GLSL
#define LC_DRAW_CONSTANTS_GLSL

#include "lightcuts/device/gpu_structs.h"

layout(push_constant) uniform DrawConstants { GpuDrawConstants draw; };

#endif
