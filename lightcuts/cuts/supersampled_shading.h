#pragma once
// Shading a supersampled image (several jittered eye rays per pixel, averaged
// into the pixel) either with one lightcut per eye ray, or with the paper's
// reconstruction cuts (Sec. 7): the image in 16x16 blocks, each started as
// 4x4 blocks with lightcut samples at their corners (a corner on the edge of
// two image blocks is computed once and shared: the image is the same);
// a block whose eye rays and corners do not match (material, normals within
// 30 degrees, the cone test for local shadowing) splits into four, down to a
// pixel, where an eye ray takes the corners that match it (two at least) or
// else a lightcut of its own. Everything else is a reconstruction cut.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/scene_light.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc {

// What one eye ray (or a block corner's ray) hit.
struct EyeSample {
    bool geometry = false;  // false: the background (no light)
    SurfacePoint point;
    // The surface's own emission, added as it is; for the background, the
    // environment it shows along the ray.
    glm::dvec3 emitted{0.0};
};

// The eye rays of a frame: `spp` per pixel, eye ray s of every pixel offset by
// offsets[s] pixels from the pixel's centre (each in [-0.5, 0.5)), and one ray
// through every pixel corner: corner (i, j) at image position (i, j), pixel
// (x, y) spanning [x, x + 1] x [y, y + 1].
struct SupersampledFrame {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<glm::dvec2> offsets;  // one per eye ray of a pixel
    std::vector<EyeSample> eye;       // index (s * height + y) * width + x
    std::vector<EyeSample> corners;   // index j * (width + 1) + i; reconstruction only

    uint32_t spp() const { return uint32_t(offsets.size()); }
    const EyeSample& eye_at(uint32_t s, uint32_t x, uint32_t y) const {
        return eye[(size_t(s) * height + y) * width + x];
    }
};

enum class SupersampleShading : uint8_t {
    kPerSampleLightcuts = 0,  // a lightcut for every eye ray
    kReconstructionCuts = 1,  // lightcuts at sparse samples, reconstruction cuts between
};

struct SupersampleStats {
    uint64_t shadow_rays = 0;          // counted as ShadowRayCount does
    uint64_t lightcuts = 0;            // lightcuts computed (samples, or every eye ray)
    uint64_t reconstruction_cuts = 0;  // eye rays shaded by reconstruction cuts
    uint64_t pixel_blocks = 0;         // blocks split down to one pixel
    double cpu_ms = 0.0;               // the workers' CPU time (user + system), summed
};

// The mean radiance of each pixel's eye rays (row-major), with the classic
// lights shaded exactly at every eye ray. Blocks are spread over `threads`
// workers; the result does not depend on their number.
std::vector<glm::dvec3> shade_supersampled(const WalkTree& tree, std::span<const SceneLight> classic_lights,
                                           const SupersampledFrame& frame, const CutSettings& settings,
                                           SupersampleShading shading, uint32_t threads,
                                           SupersampleStats& stats);

// `count` jittered sub-pixel offsets: one per cell of the smallest square grid
// holding `count` (cells taken in a seeded order when count is not a square),
// uniform within its cell, from `seed` through seeded_mixer.h.
std::vector<glm::dvec2> jittered_offsets(uint32_t count, uint64_t seed);

}  // namespace lc
