#pragma once
// The shading model in double precision for the CPU evaluator: range window,
// inverse square, spot attenuation and a light's G. The formulas are written
// once, in device/shading.glsl.h, which the shaders include as GLSL.
#include "lightcuts/device/shading.glsl.h"
