#pragma once
// The material model in double precision for the CPU evaluator and the scene
// analysis: lobe exponent, glossy lobe, glTF parameters to diffuse + lobe,
// mirror direction and f_r. The formulas are written once, in
// device/material.glsl.h, which the shaders include as GLSL.
#include "lightcuts/device/material.glsl.h"
