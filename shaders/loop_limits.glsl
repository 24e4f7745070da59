// llvmpipe (Mesa's lavapipe) stops a shader invocation's loops, silently, once
// they have iterated 65,535 times in total (its loop limiter counts every back
// edge of every loop). Loops whose trip count grows with the number of lights or
// nodes therefore do kLoopUnroll steps per iteration, written out by hand, and
// the renderer refuses work that would still exceed the budget
// (Renderer::check_loop_budget) instead of returning a truncated sum.
#ifndef LC_LOOP_LIMITS_GLSL
#define LC_LOOP_LIMITS_GLSL

const uint kLoopUnroll = 4u;    // light loops (reference, classic lights)
const uint kRadiusUnroll = 8u;  // the radius criterion's tree walk
const uint kWalkUnroll = 2u;    // the bound criterion's walk (checks its own completion)

#endif
