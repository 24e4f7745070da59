#pragma once
// What one frame shows and how: mode, cut criterion, size, camera, exposure.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "editor_client/render/settings/restir_settings.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/name_table.h"
#include "lightcuts/scene.h"
#include "lightcuts/result.h"

namespace lc::client {

// How the G-buffer is made: rasterised (GBufferPass) or cast as rays in
// compute (PrimaryRaysPass: faster where the GPU rasterises on few units).
enum class PrimaryVisibility : uint8_t { kRaster = 0, kRays = 1 };
inline constexpr NameTable<PrimaryVisibility, 2> kPrimaryVisibilityNames{{
    {"raster", PrimaryVisibility::kRaster},
    {"rays", PrimaryVisibility::kRays},
}};
const char* primary_visibility_name(PrimaryVisibility primary);
// The renderer's choice (RendererOptions::primary): auto casts rays on a GPU
// (not on a CPU device such as lavapipe, which rasterises fast) when no
// material needs the raster pass's textures.
enum class PrimaryChoice : uint8_t { kAuto = 0, kRaster = 1, kRays = 2 };
inline constexpr NameTable<PrimaryChoice, 3> kPrimaryChoiceNames{{
    {"auto", PrimaryChoice::kAuto},
    {"raster", PrimaryChoice::kRaster},
    {"rays", PrimaryChoice::kRays},
}};
std::optional<PrimaryChoice> parse_primary_choice(std::string_view text);

enum class RenderMode : uint8_t {
    kReference = 0,  // every tree leaf (or scene light) plus the classic lights, exact
    kLightcuts = 1,  // one cut per pixel, each cut node evaluated as a cluster
    kCuts = 2,       // each distinct cut a stable colour
    kCutSize = 3,    // heatmap of cut nodes per pixel with a colour scale bar
    // Stochastic lightcuts with a fixed shadow-ray budget, accumulated over
    // frames (RealtimePass): noise that converges instead of a bias.
    kRealtime = 4,
    // ReSTIR DI (RestirPass): candidates resampled per pixel and reused
    // across neighbours and frames, one shadow ray per pixel.
    kRestir = 5,
};
// In the order of the view's number keys and the editor's mode list.
inline constexpr NameTable<RenderMode, 6> kRenderModeNames{{
    {"reference", RenderMode::kReference},
    {"lightcuts", RenderMode::kLightcuts},
    {"cuts", RenderMode::kCuts},
    {"cutsize", RenderMode::kCutSize},
    {"realtime", RenderMode::kRealtime},
    {"restir", RenderMode::kRestir},
}};
inline constexpr int kRenderModeCount = int(kRenderModeNames.size());
// Modes that render a frame's light from draws and accumulate still frames
// (a history advanced per frame, dropped on a new tree or new lights).
inline bool mode_accumulates(RenderMode mode) {
    return mode == RenderMode::kRealtime || mode == RenderMode::kRestir;
}

const char* render_mode_name(RenderMode mode);
std::optional<RenderMode> parse_render_mode(std::string_view text);
// Modes that select a cut from the tree (and so need one).
inline bool mode_needs_tree(RenderMode mode) { return mode != RenderMode::kReference; }
// Modes that search a cut per pixel with a criterion (the real-time mode
// refines one per block its own way, and draws its representatives).
inline bool mode_searches_cuts(RenderMode mode) {
    return mode_needs_tree(mode) && !mode_accumulates(mode);
}
// Modes whose display is tone-mapped radiance (the others visualise cuts).
inline bool mode_is_shaded(RenderMode mode) {
    return mode == RenderMode::kReference || mode == RenderMode::kLightcuts ||
           mode_accumulates(mode);
}

inline constexpr NameTable<CutCriterion, 2> kCriterionNames{{
    {"radius", CutCriterion::kRadius},
    {"bound", CutCriterion::kBound},
}};
const char* criterion_name(CutCriterion criterion);
std::optional<CutCriterion> parse_criterion(std::string_view text);

inline constexpr NameTable<BoundSearch, 2> kBoundSearchNames{{
    {"walk", BoundSearch::kWalk},
    {"heap", BoundSearch::kHeap},
}};
const char* bound_search_name(BoundSearch search);
std::optional<BoundSearch> parse_bound_search(std::string_view text);

inline constexpr NameTable<Representatives, 3> kRepresentativesNames{{
    {"tree", Representatives::kTree},
    {"pixel", Representatives::kPixel},
    {"importance", Representatives::kImportance},
}};
const char* representatives_name(Representatives representatives);
std::optional<Representatives> parse_representatives(std::string_view text);

// Right-handed, +Y up, looking from eye to target (glTF conventions).
struct RenderCamera {
    glm::vec3 eye{0.0f, 0.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfov = 0.8f;  // radians

    bool operator==(const RenderCamera&) const = default;
};

// Rows at the bottom of a cutsize image given to the colour scale bar.
inline constexpr uint32_t kScaleBarRows = 16;

// The real-time mode's shadow rays per pixel unless asked otherwise (render
// --realtime-rays; 0: one per cut node). One per node by default: on a GPU
// its rays cost little (docs/BENCHMARKS.md: 1 ms of 5.5 at K = 16 on an H200),
// and with draws spread over frames it reaches a given error sooner than a
// budget of 4 on lavapipe too; a budget (1 to 8) is for slow devices.
inline constexpr uint32_t kDefaultRealtimeRays = 0;

// The real-time mode's shadow rays per pixel and frame at most: the budget,
// or one per cut node where it is 0 or the cut is smaller.
inline uint32_t realtime_ray_budget(uint32_t cut, uint32_t rays) {
    return rays == 0 || rays > cut ? cut : rays;
}

// Cut nodes a reconstruction sample records unless asked otherwise (render
// --reconstruction-cap): 4 bytes each.
inline constexpr uint32_t kDefaultReconstructionCap = 1024;
// The largest block side of reconstruction cuts.
inline constexpr uint32_t kMaxReconstructionBlock = 64;

struct RenderSettings {
    RenderMode mode = RenderMode::kReference;
    CutCriterion criterion = CutCriterion::kRadius;
    uint32_t width = 512;
    uint32_t height = 512;
    RenderCamera camera;
    float exposure = 1.0f;  // linear scale applied before the tone curve
    // Bound criterion (paper Sec. 4): refine until every node's error bound is
    // <= error_ratio x the pixel's total estimate, or the cut holds max_cut nodes.
    float error_ratio = 0.02f;
    uint32_t max_cut = kDefaultMaxCut;
    BoundSearch bound_search = BoundSearch::kWalk;  // how the bound criterion finds the cut
    // The walk search refines one cut per subgroup of neighbouring pixels,
    // fine enough for each of them (Lin and Yuksel 2020's cut sharing, here
    // deterministic): coherent shadow rays, each pixel stopping under its own rule.
    bool share_cuts = false;
    // The bound criterion's clusters are evaluated through the tree's
    // representatives or through ones drawn per pixel (cpu_evaluator.h,
    // Representatives); the seed of the per-pixel draws.
    Representatives representatives = Representatives::kTree;
    uint32_t representative_seed = 0;
    // Where each pixel's eye ray passes, in pixels from the pixel's centre
    // (supersampling's jitter; each component in [-0.5, 0.5]).
    glm::vec2 pixel_offset{0.0f};
    // The frame's pixels are the corners of the pixels of a (width - 1) x
    // (height - 1) image seen by the same camera (reconstruction cuts' samples).
    bool corner_grid = false;
    // The real-time mode (RenderMode::kRealtime): nodes in each 8x8 block's
    // cut, so at most this many shadow rays per pixel and frame.
    uint32_t realtime_cut = 16;
    // Its shadow rays per pixel and frame, picked among the cut's drawn lights
    // by their unshadowed radiance (shaders/shadow_ray_budget.glsl); 0 traces
    // one per cut node.
    uint32_t realtime_rays = kDefaultRealtimeRays;
    // Reconstruction cuts on the GPU (ReconstructionPass): full lightcuts at
    // the corners of blocks of this many pixels a side, the other pixels
    // reconstructed from them; 0 lightcuts every pixel. Each sample keeps at
    // most reconstruction_cap cut nodes (over it, its blocks' pixels run
    // lightcuts of their own), so the records take at most
    // reconstruction_bytes() (passes/reconstruction_records.h).
    uint32_t reconstruction_block = 0;
    uint32_t reconstruction_cap = kDefaultReconstructionCap;
    RestirSettings restir;  // RenderMode::kRestir

    bool operator==(const RenderSettings&) const = default;
};

// Largest max-cut the GPU accepts (the heap search keeps it in private memory per invocation).
inline constexpr uint32_t kMaxGpuCut = 4096;

// Largest image side, and the field of view's upper end (just under 180 degrees).
inline constexpr uint32_t kMaxImageSide = 16384;
inline constexpr float kMaxFieldOfView = 3.14f;

// What validate() needs to know besides the settings.
struct ValidationContext {
    bool has_tree = true;  // a light tree is held, or will be (cut modes need one)
    // The accepted error ratios (the editor's control is narrower than what renders).
    float min_error_ratio = 0.0f;
    float max_error_ratio = std::numeric_limits<float>::infinity();
};

// Every check on render settings, in one place (the render and view commands,
// the editor session and the renderer call it); the message names the field.
Status validate(const RenderSettings& settings, const ValidationContext& context = {});

// "ex,ey,ez,tx,ty,tz,fovy_degrees".
Result<RenderCamera> parse_camera(std::string_view text);
// "WxH", each in [1, 16384].
Result<std::pair<uint32_t, uint32_t>> parse_size(std::string_view text);

// For scenes without a camera: one that sees the whole geometry (or, without
// geometry, the scene bounds) from +Z, slightly above.
RenderCamera frame_scene_bounds(const Scene& scene, float aspect);
RenderCamera camera_from_scene(const Camera& camera);

}  // namespace lc::client
