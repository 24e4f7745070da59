// The ReSTIR mode's reservoirs (Bitterli et al. 2020, Sec. 3): weighted
// reservoir sampling over candidate lights, and the merge of reservoirs made
// elsewhere (the previous frame, neighbouring pixels). A candidate y drawn
// with pdf p(y) weighs p_hat(y) / p(y); a merged reservoir r weighs
// p_hat(r.y) * W_r * M_r, p_hat evaluated here. The survivor's contribution
// weight is W = w_sum / (M p_hat(y)) (biased, 1/M) or w_sum / (Z p_hat(y))
// with Z the candidates of the merged reservoirs that could have produced y
// (unbiased, 1/Z). The pixel's random numbers: a hash chain of its own.
#ifndef LC_RESTIR_RESERVOIR_GLSL
#define LC_RESTIR_RESERVOIR_GLSL

#include "lightcuts/device/cut_hash.glsl.h"
#include "lightcuts/device/restir.h"

// A reservoir being built: the sample, the running weight sum and the
// candidates seen; `target` is the sample's p_hat here.
struct Reservoir {
    uint light;
    float weight_sum;
    float count;
    float target;
    bool has_sample;
};

Reservoir empty_reservoir() { return Reservoir(0u, 0.0, 0.0, 0.0, false); }

// The pixel's random state and its next uniform in [0, 1).
uint g_restir_random = 0u;

void seed_restir_random(ivec2 pixel, uint frame_seed, uint stage) {
    g_restir_random = cut_hash_term(cut_hash_term(cut_hash_term(frame_seed ^ 0x2545F491u) ^ uint(pixel.x)) ^
                                    (uint(pixel.y) + (stage << 24u)));
}

float restir_uniform() {
    g_restir_random = cut_hash_term(g_restir_random + 0x9E3779B9u);
    return float(g_restir_random >> 8u) * (1.0 / 16777216.0);
}

// Offers a sample of weight w standing for `count` candidates. A non-finite
// or non-positive weight counts its candidates and cannot be kept.
void reservoir_offer(inout Reservoir r, uint light, float w, float count, float target) {
    r.count += count;
    if (!(w > 0.0) || !(w < 3.402823466e38)) return;
    r.weight_sum += w;
    if (restir_uniform() * r.weight_sum < w) {
        r.light = light;
        r.target = target;
        r.has_sample = true;
    }
}

// W = w_sum / (normaliser x p_hat(y)), 0 without a sample.
float contribution_weight(Reservoir r, float normaliser) {
    if (!r.has_sample || !(r.target > 0.0) || !(normaliser > 0.0)) return 0.0;
    return r.weight_sum / (normaliser * r.target);
}

GpuReservoir stored_reservoir(Reservoir r, float weight, vec3 position, vec3 normal) {
    GpuReservoir g;
    g.position = position;
    g.light = r.light;
    g.normal = normal;
    g.weight = r.has_sample ? weight : 0.0;
    g.count = r.count;
    g.target = r.has_sample ? r.target : 0.0;
    g.pad0 = 0.0;
    g.pad1 = 0.0;
    return g;
}

#endif
