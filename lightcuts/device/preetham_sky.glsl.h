// The Preetham, Shirley and Smits (1999) daylight model, written once: the
// client's background shader includes it as GLSL (float), lightcuts/preetham_sky.h
// as C++ (double) in lc::sky, so what the server samples is what the client draws.
// Radiance is linear sRGB in kcd/m^2, the paper's unit for luminance; directions
// are unit, +Y up; below the horizon the sky is black (the scene is the ground).
#ifndef LC_DEVICE_PREETHAM_SKY_GLSL_H
#define LC_DEVICE_PREETHAM_SKY_GLSL_H

#include "lightcuts/device/real_math.glsl.h"

#ifdef __cplusplus
namespace lc::sky {
using namespace lc::device;
using std::cos;
using std::exp;
using std::tan;
#endif

LC_CONST real kSkyPi = 3.14159265358979323846;
// The sun's angular radius (0.2667 degrees) and its radiance above the
// atmosphere as luminance: 128 klux over its 6.8e-5 sr.
LC_CONST real kSunAngularRadius = 0.004654;
LC_CONST real kSunLuminanceAboveAtmosphere = 1.88e6;

// Perez et al.'s luminance distribution, Preetham Eq. 3.
LC_INLINE real perez(real A, real B, real C, real D, real E, real cos_theta, real gamma) {
    real cos_gamma = cos(gamma);
    return (1.0 + A * exp(B / max(cos_theta, 1e-3))) * (1.0 + C * exp(D * gamma) + E * cos_gamma * cos_gamma);
}

// Y (kcd/m^2), x, y of a sky direction at zenith angle theta and angle gamma
// from the sun at zenith angle theta_s, turbidity T: Preetham Appendix A.2.
LC_INLINE real3 preetham_Yxy(real cos_theta, real gamma, real theta_s, real T) {
    real chi = (4.0 / 9.0 - T / 120.0) * (kSkyPi - 2.0 * theta_s);
    real zenith_Y = (4.0453 * T - 4.9710) * tan(chi) - 0.2155 * T + 2.4192;
    real t2 = theta_s * theta_s;
    real t3 = t2 * theta_s;
    real zenith_x = T * T * (0.00166 * t3 - 0.00375 * t2 + 0.00209 * theta_s) +
                    T * (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * theta_s + 0.00394) +
                    (0.11693 * t3 - 0.21196 * t2 + 0.06052 * theta_s + 0.25886);
    real zenith_y = T * T * (0.00275 * t3 - 0.00610 * t2 + 0.00317 * theta_s) +
                    T * (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * theta_s + 0.00516) +
                    (0.15346 * t3 - 0.26756 * t2 + 0.06670 * theta_s + 0.26688);
    real Y = zenith_Y *
             perez(0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771,
                   -0.0670 * T + 0.3703, cos_theta, gamma) /
             perez(0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771,
                   -0.0670 * T + 0.3703, 1.0, theta_s);
    real x = zenith_x *
             perez(-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989,
                   -0.0033 * T + 0.0452, cos_theta, gamma) /
             perez(-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989,
                   -0.0033 * T + 0.0452, 1.0, theta_s);
    real y = zenith_y *
             perez(-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537,
                   -0.0109 * T + 0.0529, cos_theta, gamma) /
             perez(-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537,
                   -0.0109 * T + 0.0529, 1.0, theta_s);
    return real3(Y, x, y);
}

// CIE xyY to linear sRGB (D65), negative components clipped.
LC_INLINE real3 Yxy_to_linear_srgb(real3 Yxy) {
    real Y = Yxy.x;
    real X = Yxy.y / Yxy.z * Y;
    real Z = (1.0 - Yxy.y - Yxy.z) / Yxy.z * Y;
    real3 rgb = real3(3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
                      0.0557 * X - 0.2040 * Y + 1.0570 * Z);
    return max(rgb, real3(0.0, 0.0, 0.0));
}

// The sky without the sun along a unit direction, for a unit sun direction.
LC_INLINE real3 preetham_sky_radiance(real3 direction, real3 sun, real turbidity) {
    if (direction.y <= 0.0) return real3(0.0, 0.0, 0.0);
    real theta_s = acos(clamp(sun.y, -1.0, 1.0));
    real gamma = acos(clamp(dot(direction, sun), -1.0, 1.0));
    return Yxy_to_linear_srgb(preetham_Yxy(direction.y, gamma, theta_s, turbidity));
}

// Transmittance of the direct sun at wavelength lambda (micrometres): Rayleigh
// and aerosol (Angstrom, alpha = 1.3) extinction over the relative optical
// mass of Kasten's formula, Preetham Appendix A.1 without ozone and water.
LC_INLINE real sun_transmittance(real lambda, real theta_s, real turbidity) {
    real theta_deg = theta_s * 180.0 / kSkyPi;
    real mass = 1.0 / (cos(theta_s) + 0.15 * pow(max(93.885 - theta_deg, 1e-3), -1.253));
    real beta = 0.04608 * turbidity - 0.04586;
    return exp(-mass * (0.008735 * pow(lambda, -4.08) + beta * pow(lambda, -1.3)));
}

// Radiance inside the sun's disc (uniform: no limb darkening), red, green and
// blue taken at 680, 550 and 440 nm.
LC_INLINE real3 preetham_sun_radiance(real3 sun, real turbidity) {
    if (sun.y < 0.0) return real3(0.0, 0.0, 0.0);
    real theta_s = acos(clamp(sun.y, -1.0, 1.0));
    return kSunLuminanceAboveAtmosphere *
           real3(sun_transmittance(0.680, theta_s, turbidity), sun_transmittance(0.550, theta_s, turbidity),
                 sun_transmittance(0.440, theta_s, turbidity));
}

#ifdef __cplusplus
}  // namespace lc::sky
#endif

#endif
