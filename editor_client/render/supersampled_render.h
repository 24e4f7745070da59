#pragma once
// `render --spp N`: N jittered eye rays per pixel (jittered_offsets, seeded;
// one ray through the pixel's centre for N = 1), resolved into the pixel by
// their mean, shaded one of three ways:
//   gpu             N whole frames on the GPU (lightcuts or reference as the
//                   settings' mode says), one per eye-ray offset;
//   lightcuts       a CPU lightcut (bound criterion, heap search) per eye ray;
//   reconstruction  the paper's reconstruction cuts (supersampled_shading.h)
//                   over the same eye rays, CPU lightcuts at sparse samples.
// The two CPU methods rasterise their eye rays (and the corner samples) on the
// GPU as G-buffers and shade them with the CPU evaluator, so they compare on
// equal terms: same code, same shadow-ray count.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/renderer.h"
#include "lightcuts/name_table.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"
#include "lightcuts/cuts/supersampled_shading.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc::client {

enum class SppMethod : uint8_t { kGpu = 0, kLightcuts = 1, kReconstruction = 2 };
inline constexpr NameTable<SppMethod, 3> kSppMethodNames{{
    {"gpu", SppMethod::kGpu},
    {"lightcuts", SppMethod::kLightcuts},
    {"reconstruction", SppMethod::kReconstruction},
}};
const char* spp_method_name(SppMethod method);
std::optional<SppMethod> parse_spp_method(std::string_view text);

// The eye-ray offsets' seed when none is given.
inline constexpr uint64_t kDefaultSppSeed = 1;

struct SupersampledImage {
    std::vector<float> hdr;  // RGBA per pixel, the mean of its eye rays
    // GPU time of the frames (gpu), or wall time of the CPU shading (the
    // G-buffers' rasterisation left out: both CPU methods share it).
    double shading_ms = 0.0;
    uint64_t shadow_rays = 0;
    uint64_t nonfinite_pixels = 0;  // written as 0
    SupersampleStats cpu;           // the CPU methods' counts
};

struct SupersampleRequest {
    uint32_t spp = 1;
    SppMethod method = SppMethod::kGpu;
    uint64_t seed = kDefaultSppSeed;
    uint32_t threads = 1;  // CPU methods: workers
};

// `tree` and `classic_lights` are what the renderer holds (the CPU methods
// read them); the renderer keeps the last frame's targets.
Result<SupersampledImage> render_supersampled(Renderer& renderer, const RenderSettings& settings,
                                              const SupersampleRequest& request, const WalkTree* tree,
                                              std::span<const SceneLight> classic_lights);

}  // namespace lc::client
