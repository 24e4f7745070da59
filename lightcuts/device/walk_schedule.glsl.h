// The thresholds of the bound criterion's walk search (lightcuts/cuts/bound_walk.h),
// written once: shaders/lightcuts_bound_walk.comp includes it as GLSL (float),
// bound_walk.cpp as C++ (double) in lc::device.
#ifndef LC_DEVICE_WALK_SCHEDULE_GLSL_H
#define LC_DEVICE_WALK_SCHEDULE_GLSL_H

#include "lightcuts/device/real_math.glsl.h"

#ifdef __cplusplus
namespace lc::device {
#endif

// After a pass whose cut fit but missed the rule: just under the rule's limit
// (margin < 1), or the largest bound on the cut shrunk, whichever is larger.
LC_INLINE real next_walk_threshold(real limit, real worst, real margin, real shrink) {
    return max(margin * limit, worst / shrink);
}

// Between a threshold whose cut fit (fit_hi: the largest bound on that cut)
// and one whose cut exceeded max_cut (over_lo): their geometric mean, with
// over_lo kept above fit_hi x 1e-6 so that a zero makes progress.
LC_INLINE real bisection_threshold(real fit_hi, real over_lo) {
    return sqrt(fit_hi) * sqrt(max(over_lo, fit_hi * 1e-6));
}

#ifdef __cplusplus
}  // namespace lc::device
#endif

#endif
