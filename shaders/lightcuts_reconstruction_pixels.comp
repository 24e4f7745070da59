#version 460
// Reconstruction cuts, second dispatches: every pixel that is not a sample
// (lightcuts_reconstruction_samples.comp stored those) is shaded from the
// four samples at its block's corners by reconstruction_walk.glsl, tracing
// shadow rays only where the samples' visibility of a cluster disagrees.
// Only the corners on the pixel's surface take part: a corner that differs
// from the pixel in normal, depth or material (across a silhouette, a crease,
// a thin feature) or whose sample is not usable is left out, its weight
// shared among the others. Where fewer than two are left (one sample alone
// would stretch its shadows over the block), the pixel runs the bound
// walk search of its own (bound_walk.glsl) over the same dispatches as
// lightcuts_bound_walk.comp; so does a pixel whose reconstruction the loop
// limit cut short or pushed over max-cut, from the next dispatch on.
#extension GL_GOOGLE_include_directive : require

#include "bound_walk.glsl"
#include "reconstruction_walk.glsl"

// A corner agrees with the pixel when its normal is within about 18 degrees,
// it lies within 1% of the eye distance of the pixel's tangent plane, and
// its material's parameters differ by at most 0.02.
const float kNormalAgreement = 0.95;
const float kPlaneTolerance = 0.01;
const float kMaterialTolerance = 0.02;
const uint kMinAgreeingCorners = 2u;

struct BlockCorners {
    uint sample_index[4];
    ivec2 pixel[4];
    float weight[4];  // bilinear, summing to 1
};

BlockCorners block_corners(ivec2 pixel) {
    uvec2 lattice = sample_lattice_size();
    uvec2 c0 = min(uvec2(pixel) / kBlock, lattice - 1u);
    uvec2 c1 = min(c0 + 1u, lattice - 1u);
    ivec2 p0 = sample_pixel(c0);
    ivec2 p1 = sample_pixel(c1);
    vec2 f = vec2(0.0);
    if (p1.x > p0.x) f.x = float(pixel.x - p0.x) / float(p1.x - p0.x);
    if (p1.y > p0.y) f.y = float(pixel.y - p0.y) / float(p1.y - p0.y);
    BlockCorners c;
    c.sample_index = uint[4](c0.y * lattice.x + c0.x, c0.y * lattice.x + c1.x, c1.y * lattice.x + c0.x,
                             c1.y * lattice.x + c1.x);
    c.pixel = ivec2[4](p0, ivec2(p1.x, p0.y), ivec2(p0.x, p1.y), p1);
    c.weight = float[4]((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    return c;
}

bool corner_agrees(ivec2 corner, uint sample_index, ivec2 pixel, float eye_distance) {
    if ((samples[sample_index].flags & kSampleUsable) == 0u) return false;
    vec4 n = imageLoad(gbuffer_normal, pixel);
    vec4 nc = imageLoad(gbuffer_normal, corner);
    vec3 offset = imageLoad(gbuffer_position, corner).xyz - imageLoad(gbuffer_position, pixel).xyz;
    vec4 material = abs(imageLoad(gbuffer_albedo, corner) - imageLoad(gbuffer_albedo, pixel));
    return dot(nc.xyz, n.xyz) >= kNormalAgreement && abs(dot(n.xyz, offset)) <= kPlaneTolerance * eye_distance &&
           max(max(material.x, material.y), max(material.z, material.w)) <= kMaterialTolerance &&
           abs(nc.w - n.w) <= kMaterialTolerance;
}

// The pixel shaded from its block's samples, or false where it must run a
// lightcut of its own from this dispatch on.
bool reconstruct_pixel(ivec2 pixel) {
    uint index = uint(pixel.y) * frame.width + uint(pixel.x);
    set_pixel_representatives(pixel);
    SurfacePoint p;
    if (!load_surface(pixel, p)) {
        store_background(pixel);
        walk_states[index].flags = kWalkDone;
        return true;
    }
    BlockCorners c = block_corners(pixel);
    float eye_distance = length(p.position - frame.eye);
    // The agreeing corners; a left-out one is replaced by an agreeing one of
    // weight 0 (the same sample twice changes no rule).
    int first_agreeing = -1;
    float weight_sum = 0.0;
    uint count = 0u;
    bool agrees[4];
    for (uint k = 0u; k < 4u; ++k) {
        agrees[k] = corner_agrees(c.pixel[k], c.sample_index[k], pixel, eye_distance);
        if (agrees[k] && first_agreeing < 0) first_agreeing = int(k);
        if (agrees[k]) weight_sum += c.weight[k];
        if (agrees[k]) ++count;
    }
    if (count < kMinAgreeingCorners) {
        atomicAdd(counters.reconstruction_fallbacks, 1u);
        return false;
    }
    vec3 total = vec3(0.0);
    // Corners stopped by max-cut reached a looser ratio; refining finer than
    // the coarsest of them would outgrow the pixel's cut.
    float ratio = kErrorRatio;
    for (uint k = 0u; k < 4u; ++k) {
        if (agrees[k]) ratio = max(ratio, samples[c.sample_index[k]].reached_ratio);
        uint sample_index = agrees[k] ? c.sample_index[k] : c.sample_index[first_agreeing];
        // All agreeing corners of weight 0 (the pixel on a lattice line): equal shares.
        float weight = weight_sum > 0.0 ? (agrees[k] ? c.weight[k] / weight_sum : 0.0) : (agrees[k] ? 1.0 : 0.0);
        total += weight * samples[sample_index].radiance;
        begin_sample_cursor(k, sample_index);
    }
    if (!(weight_sum > 0.0)) total /= float(count);
    ReconstructionCut cut;
    if (!reconstruction_walk(ratio * max(max_channel(total), 0.0), p, cut)) {
        // The lightcut starts in the next dispatch, with a fresh loop budget.
        atomicAdd(counters.reconstruction_fallbacks, 1u);
        walk_states[index] = walk_start();
        g_shadow_walk_cut_short = false;
        flush_shadow_ray_count();
        return true;
    }
    walk_states[index].flags = kWalkDone;
    vec3 radiance = clamp_indirect(pixel, cut.radiance, cut.indirect);
    store_pixel(pixel, radiance + classic_and_emitted_radiance(p), cut.size, cut.hash, false);
    return true;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height) || is_sample_pixel(pixel)) return;
    if (frame.walk_dispatch == 0u && reconstruct_pixel(pixel)) return;
    bound_walk_dispatch(pixel);
}
