// llvmpipe (Mesa's lavapipe) stops a shader invocation's loops, silently, once
// they have iterated 65,535 times in total (its loop limiter counts every back
// edge of every loop). Loops whose trip count grows with the number of lights
// or nodes therefore do several steps per iteration, written out by hand, and
// the renderer refuses work that would still exceed the budget
// (Renderer::check_loop_budget) instead of returning a truncated sum: both
// count iterations with the unroll counts below.
#ifndef LC_DEVICE_LIMITS_H
#define LC_DEVICE_LIMITS_H

#include "lightcuts/device/glsl_compat.h"

LC_DEVICE_BEGIN

LC_CONST uint kLoopUnroll = 4u;    // light loops (reference, classic lights)
LC_CONST uint kRadiusUnroll = 8u;  // the radius criterion's tree walk
LC_CONST uint kWalkUnroll = 2u;    // the bound criterion's walk (checks its own completion)
// Shadow BVH node visits per loop iteration. One: the walk is inlined wherever
// a light is shaded (four times in the reference's loop body, eight in the
// radius walk's), and more copies made lavapipe's shader compile take seconds
// and the bound walk 2x slower (measured: 4 visits per iteration, 16,384
// lights, 2.4 s against 1.1 s).
LC_CONST uint kShadowUnroll = 1u;
// The real-time mode's cut per 8x8 block: at most this many nodes (Lin and
// Yuksel 2020 use 32), each one drawn light and one shadow ray per pixel.
LC_CONST uint kMaxStochasticCut = 32u;
// The real-time mode's shadow-ray budget (RenderSettings::realtime_rays): at
// most this many rays per pixel, picked among the cut's drawn lights.
LC_CONST uint kMaxStochasticRays = 8u;
// Invocations in a compute workgroup at most (RendererOptions::workgroup_size
// squared): the real-time mode's block keeps one flag per pixel in shared memory.
LC_CONST uint kMaxWorkgroupInvocations = 256u;

LC_DEVICE_END

#endif
