// Where a direction falls on an equirectangular map (lightcuts/equirect_map.h
// states the mapping), written once: the client's background shader includes
// it as GLSL (float), equirect_map.cpp as C++ (double) in lc::equirect, so
// the texel the background shows is the texel the server sampled.
#ifndef LC_DEVICE_EQUIRECT_MAP_GLSL_H
#define LC_DEVICE_EQUIRECT_MAP_GLSL_H

#include "lightcuts/device/real_math.glsl.h"

#ifdef __cplusplus
namespace lc::equirect {
using namespace lc::device;
using std::floor;
// GLSL's two-argument atan.
inline real atan(real y, real x) { return std::atan2(y, x); }
#endif

LC_CONST real kEquirectPi = 3.14159265358979323846;

// u in [0, 1): the angle about +Y from +X towards +Z, less the map's rotation
// (radians), as a fraction of a turn. `d` is unit.
LC_INLINE real equirect_u(real3 d, real rotation) {
    real u = (atan(d.z, d.x) - rotation) / (2.0 * kEquirectPi);
    u -= floor(u);
    return u >= 1.0 ? 0.0 : u;
}

// v in [0, 1]: the angle from the zenith as a fraction of a half turn.
LC_INLINE real equirect_v(real3 d) { return acos(clamp(d.y, -1.0, 1.0)) / kEquirectPi; }

#ifdef __cplusplus
}  // namespace lc::equirect
#endif

#endif
