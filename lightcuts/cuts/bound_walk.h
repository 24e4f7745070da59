#pragma once
// The bound criterion's cut found by threshold passes instead of a heap.
//
// The paper refines the node with the largest error bound until every bound is
// <= error x the total estimate. The cut that rule stops at depends on the
// threshold only through the final total T, so a walk that refines every node
// whose bound exceeds a threshold tau finds a cut meeting the same rule once
// tau <= error x T of its own cut. Each pass is a pre-order walk (no heap, no
// stack: what a SIMD device wants); a pass that misses sets a lower tau and
// walks again:
//   pass 0: tau = +inf (the cut is the per-type roots);
//   then, while the largest bound left on the cut, m, exceeds error x T:
//   tau = max(kWalkMargin x error x T, m / kWalkShrink).
// The margin makes the pass after the scale is found almost always the last;
// the shrink bounds how far one pass can over-refine on a poor early T.
// A pass whose cut would exceed max_cut is abandoned, and the passes left
// bisect (geometric mean) between the last threshold that fit and the one
// that did not, kWalkBisections times at most: the pixel keeps the finest cut
// found within max_cut (every node of it under one threshold, never a
// truncated walk) and counts as a max-cut hit, as does a pixel still refining
// after kWalkMaxPasses. (Without the bisection a pixel at the cap kept a cut
// far below it, up to kWalkShrink times coarser: found by the accuracy sweep.) Interior nodes are never evaluated, so there is nothing for
// a child to reuse; cut nodes are evaluated once per pass.
//
// shaders/lightcuts_bound_walk.comp implements the same passes (constants come from here
// as specialization constants), shared by a subgroup; a pass the device's
// loop limit cuts short runs again in the next dispatch (the search kept per
// pixel in GpuWalkState between them).
#include <cstdint>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"

namespace lc {

inline constexpr uint32_t kWalkMaxPasses = 12;
inline constexpr float kWalkShrink = 512.0f;
inline constexpr float kWalkMargin = 0.8f;
inline constexpr uint32_t kWalkBisections = 6;

// device::bisection_threshold (walk_schedule.glsl.h) in double: the next
// threshold between one whose cut fit and one whose cut exceeded max_cut.
double bisection_threshold(double fit_hi, double over_lo);

// The cut of the bound criterion by threshold passes (classic lights not
// included), with the kept pass's nodes appended to `nodes` when given (as
// bound_heap_cut does: what an audit of the cut's error reads node by node).
CutResult bound_walk_cut(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings,
                         std::vector<CutNodeEstimate>* nodes = nullptr);

}  // namespace lc
