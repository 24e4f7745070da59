// The real-time mode's uniforms, spread evenly over a still view's frames
// (stochastic_draw.glsl, shadow_ray_budget.glsl). Frame n's uniform for a
// stream (a cut node's descent, the picks) is fract(o + n a_d): o a hash of
// the pixel, the seed and the stream, the same in every frame; a_d the step of
// the stream's dimension d. Consecutive frames cover [0, 1) almost evenly (a
// Weyl sequence), so the running mean converges faster than with independent
// frames, while each frame on its own stays an unbiased estimate (o is
// uniform). Descents step by the golden ratio's 0.618 (the most even in one
// dimension), the picks by sqrt(2) - 1: 1, a_1 and a_2 are independent over
// the rationals, so the two stay evenly spread jointly, as the picks'
// unbiasedness needs (with one step for both, a node's draw would fix which
// part of [0, 1) the picks take, frame after frame, and the pixel would
// converge to a wrong answer). Descents of different nodes share a step: the
// frame's estimate sums them, so each needs only its own sequence even. The
// block's pivot stays drawn anew each frame (a hash): a pivot on a sequence
// would choose which frames keep a node in the cut, in step with its draws.
// One uniform serves a whole chain of choices: after each, the share it fell
// in is stretched back over [0, 1) (pbrt-v4's light BVH draws the same way);
// once a chain has stretched it 256x, its low bits are rounding, and a fresh
// hash (this frame's own) takes over: 16 bits of stratification are plenty
// for a few hundred frames.
#ifndef LC_FRAME_STRATA_GLSL
#define LC_FRAME_STRATA_GLSL

#include "lightcuts/device/cut_hash.glsl.h"

const float kLargestBelowOne = 0.99999994;  // 1 - 2^-24
const float kLargestStretch = 256.0;

const uint kStrataDraw = 0u;
const uint kStrataPick = 1u;
// a_d in 32-bit fixed point.
const uint kStrataStep[2] = uint[2](0x9E3779B9u, 0x6A09E668u);

// The pixel's key over frames (its seed and place only) and the frame.
uint g_strata_key = 0u;
uint g_strata_frame = 0u;

void set_frame_strata(ivec2 pixel, uint draw_seed, uint frame_number) {
    g_strata_key = cut_hash_term(cut_hash_term(cut_hash_term(draw_seed ^ 0x5BD1E995u) ^ uint(pixel.x)) ^
                                 uint(pixel.y));
    g_strata_frame = frame_number;
}

// Frame `frame_number`'s uniform in [0, 1) of dimension d for a stream whose
// offset hashes `key`, exact in float (24 bits).
float stratum_of(uint key, uint d, uint frame_number) {
    return float((cut_hash_term(key) + frame_number * kStrataStep[d]) >> 8u) * (1.0 / 16777216.0);
}

// This frame's uniform of dimension d for the pixel's `stream`.
float frame_stratum(uint d, uint stream) {
    return stratum_of(g_strata_key ^ cut_hash_term(stream ^ (d << 30u)), d, g_strata_frame);
}

// A chain's uniform and how much it has been stretched since it was fresh.
struct StratifiedChain {
    float u;
    float stretch;
};

StratifiedChain start_chain(float u) { return StratifiedChain(u, 1.0); }

// Chooses between two parts weighing w_first and w_second (a positive,
// finite sum): the first when u falls in its share, then stretches u over
// the share taken.
bool chain_takes_first(inout StratifiedChain c, float w_first, float w_second) {
    float t = c.u * (w_first + w_second);
    bool first = t < w_first || !(w_second > 0.0);
    float w = first ? w_first : w_second;
    c.u = min((first ? t : t - w_first) / w, kLargestBelowOne);
    c.stretch *= (w_first + w_second) / w;
    return first;
}

// Whether the chain's uniform has lost too many bits to go on (the caller
// starts a fresh chain from a hash).
bool chain_worn(StratifiedChain c) { return !(c.stretch <= kLargestStretch); }

#endif
