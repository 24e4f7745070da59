// The ReSTIR mode's interface between RestirPass and shaders/restir_*.comp:
// its descriptor set, its specialization constants and the reservoir each
// pixel keeps between its stages and frames (restir_reservoir.glsl).
#ifndef LC_DEVICE_RESTIR_H
#define LC_DEVICE_RESTIR_H

#include "lightcuts/device/glsl_compat.h"

LC_DEVICE_BEGIN

// The pass's own set (set 3, beside the frame's set 0, the temporal history's
// set 1 and the light-draw records' set 2): the previous frame's reservoirs
// (read by the temporal reuse), this frame's after temporal reuse (read by
// the spatial reuse) and this frame's final ones (the next frame's previous).
LC_CONST uint kRestirSet = 3u;
LC_CONST uint kBindReservoirsPrevious = 0u;
LC_CONST uint kBindReservoirsTemporal = 1u;
LC_CONST uint kBindReservoirsFinal = 2u;
LC_CONST uint kRestirBindingCount = 3u;

// Specialization constants (ids past spec_constants.h's).
LC_CONST uint kSpecRestirCandidates = 40u;  // initial candidates per pixel (M)
LC_CONST uint kSpecRestirSource = 41u;      // kRestirSource*
LC_CONST uint kSpecRestirSpatial = 42u;     // spatial neighbours (k)
LC_CONST uint kSpecRestirTemporal = 43u;    // bool: reuse the previous frame's reservoir
LC_CONST uint kSpecRestirUnbiased = 44u;    // bool: 1/Z weights instead of 1/M
LC_CONST uint kSpecRestirCandidateVisibility = 45u;  // bool: shadow ray on the candidate before reuse

LC_CONST uint kRestirSourceTree = 0u;   // the light tree's draw from the root (geometry x intensity)
LC_CONST uint kRestirSourcePower = 1u;  // the same descent weighing the children by intensity alone

// A pixel's reservoir: the sample it kept (a leaf light), its unbiased
// contribution weight W, the candidates it stands for (M), and the surface
// it was made at (for the next frame's temporal reuse).
struct LC_ALIGN16 GpuReservoir {
    vec3 position LC_DEFAULT(vec3(0.0f));
    uint light LC_DEFAULT(0u);
    vec3 normal LC_DEFAULT(vec3(0.0f));
    float weight LC_DEFAULT(0.0f);  // W; 0: no sample
    float count LC_DEFAULT(0.0f);   // M
    float target LC_DEFAULT(0.0f);  // p_hat of the sample at the surface
    float pad0 LC_DEFAULT(0.0f);
    float pad1 LC_DEFAULT(0.0f);
};

LC_DEVICE_END

#endif
