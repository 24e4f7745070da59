// The cut hash, written once for the shaders and the CPU evaluator.
#ifndef LC_CUT_HASH_GLSL
#define LC_CUT_HASH_GLSL

#include "lightcuts/device/cut_hash.glsl.h"

#endif
