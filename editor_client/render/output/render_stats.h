#pragma once
// What one render cost and produced, written as JSON by `render --stats`: the
// frame's own facts at the top, the rest in groups (timing, cuts, the
// real-time mode, reconstruction cuts, shadows, indirect light, the error
// against the reference, supersampling), each writing its own keys. The JSON
// is flat: a group adds its keys beside the frame's, named as they always were.
#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "editor_client/render/analysis/scene_effects.h"
#include "lightcuts/result.h"

namespace lc::client {

// GPU time from the first to the last timestamp, and per pass.
struct FrameTiming {
    double render_ms = 0.0;
    double gbuffer_ms = 0.0;
    double lighting_ms = 0.0;
    double output_ms = 0.0;
    double wall_ms = 0.0;  // CPU wall clock of the frame: record, submit, wait
    // The clock render_ms reads: GPU timestamps, or the CPU's wall clock
    // (render --spp-method lightcuts or reconstruction shade on the CPU).
    std::string render_clock = "GPU";
    uint32_t submissions = 1;  // command buffers the frame was submitted in

    void write_json(nlohmann::json& j) const;
};

// Cut size over pixels with geometry (reference mode: every leaf is the cut),
// and the bound criterion's settings where it searched the cuts.
struct CutStats {
    double avg_cut = 0.0;
    uint32_t max_cut = 0;
    uint32_t cut_p99 = 0;            // 99th percentile of the cut size over pixels with a cut
    uint64_t light_evaluations = 0;  // light or cluster evaluations in the lighting pass
    uint64_t max_cut_hits = 0;       // pixels whose cut stopped at max_cut_setting
    uint64_t loop_limit_stops = 0;   // pixels whose walk or shadow ray the device's loop limit cut short
    float error_ratio = 0.0f;
    uint32_t max_cut_setting = 0;  // 0: no cut was searched, and no setting is written
    // The heap search's entries (max-cut, or less where the driver refused it).
    uint32_t heap_capacity = 0;
    std::string bound_search;     // walk or heap
    std::string representatives;  // tree, pixel or importance
    uint32_t representative_seed = 0;

    void write_json(nlohmann::json& j) const;
};

// The real-time mode: nodes per block's cut, the shadow-ray budget asked for
// (0: one per cut node), and the frames its history holds after this one
// (the image is their mean). Written where cut > 0.
struct RealtimeStats {
    uint32_t cut = 0;
    uint32_t rays = 0;
    uint32_t frames = 0;

    void write_json(nlohmann::json& j) const;
};

// GPU reconstruction cuts (render --reconstruction): the block side (0: off),
// records per sample at most, the samples' storage, and the pixels between
// samples that ran a lightcut of their own.
struct ReconstructionStats {
    uint32_t block = 0;
    uint32_t cap = 0;
    uint64_t bytes = 0;
    uint64_t fallbacks = 0;

    void write_json(nlohmann::json& j) const;
};

// Shadows: simulated or not (the effects say why), rays traced, the occluders' size.
struct ShadowStats {
    bool simulated = false;
    uint64_t rays = 0;
    uint32_t triangles = 0;
    uint32_t bvh_nodes = 0;

    // shadow_rays_per_pixel is over the pixels with geometry.
    void write_json(nlohmann::json& j, uint64_t geometry_pixels) const;
};

// The tree's indirect lights: on (clamped) or off, their leaves, and the
// indirect light on the pixels' cuts before the clamp and what the clamp
// removed (summed over pixels and channels). Written where mode is set.
struct IndirectStats {
    std::string mode;  // empty without indirect lights
    uint64_t lights = 0;
    uint64_t patches = 0;  // of the indirect lights, radiosity patches (the others are VPLs)
    double energy = 0.0;
    double clamped_energy = 0.0;
    // Reference mode with VPLs: the exact clamp's Newton passes after the sums,
    // and the largest relative change of a pixel's threshold in the last one
    // (0: every pixel had reached its root).
    uint32_t reference_clamp_passes = 0;
    bool reference_visibility_kept = false;  // Newton's passes read the sums' shadow rays
    double reference_clamp_change = 0.0;

    double clamped_fraction() const { return energy > 0.0 ? clamped_energy / energy : 0.0; }
    void write_json(nlohmann::json& j) const;
};

// Lightcuts against the reference rendered in the same run (error_stats.h).
struct ErrorSummary {
    bool measured = false;
    double rel_err_mean = 0.0;
    double rel_err_p99 = 0.0;
    double frac_over_error = 0.0;
    double max_err = 0.0;
    uint64_t pixels = 0;          // pixels with a non-negligible reference
    double reference_ms = 0.0;    // GPU time of the reference frame
    double frac_over_2pct = 0.0;  // measured pixels whose relative error exceeds 2%
    uint64_t reference_shadow_rays = 0;

    // The reference's shadow rays are written for a supersampled frame only.
    void write_json(nlohmann::json& j, bool supersampled) const;
};

// Supersampling (render --spp): eye rays per pixel and how they were shaded;
// the CPU methods' lightcuts and reconstruction cuts.
struct SupersamplingStats {
    uint32_t spp = 1;
    std::string method = "gpu";
    uint64_t lightcuts_computed = 0;
    uint64_t reconstruction_cuts = 0;
    double shading_cpu_ms = 0.0;  // CPU methods: the workers' CPU time (render_ms is wall)

    bool supersampled() const { return spp > 1 || method != "gpu"; }
    void write_json(nlohmann::json& j) const;
};

struct RenderStats {
    std::string scene;
    std::string mode;
    std::string primary = "raster";  // how the G-buffer was made: raster or rays
    std::string criterion;
    std::string device;
    uint32_t width = 0;
    uint32_t height = 0;
    uint64_t lights = 0;  // evaluated by reference mode: tree leaves (or scene lights) + classic
    uint64_t tree_lights = 0;  // leaves of the tree (0 without a tree)
    uint64_t classic_lights = 0;
    uint64_t nodes = 0;  // tree nodes
    uint32_t tree_depth = 0;
    uint64_t geometry_pixels = 0;
    uint64_t nonfinite_pixels = 0;
    std::vector<EffectDecision> effects_simulated;
    std::vector<EffectDecision> effects_skipped;
    uint32_t reference_dispatches = 0;  // reference mode: dispatches the leaves were split over
    // Every pixel_stride-th pixel in x and y was rendered (render --pixel-stride): the
    // image holds only those, and its time is theirs.
    uint32_t pixel_stride = 1;
    // Not 1: the stride was over tiles of this many pixels a side (render
    // --tile-stride), each rendered whole; the image holds the tiles side by side.
    uint32_t stride_tile = 1;
    double exposure = 1.0;  // the exposure the PNG was tone-mapped with
    bool auto_exposure = false;
    uint32_t validation_messages = 0;
    bool validation_enabled = false;

    FrameTiming timing;
    CutStats cuts;
    RealtimeStats realtime;
    ReconstructionStats reconstruction;
    ShadowStats shadows;
    IndirectStats indirect;
    ErrorSummary error;
    SupersamplingStats supersampling;
};

nlohmann::json stats_json(const RenderStats& stats);
Status write_stats_json(const std::filesystem::path& path, const RenderStats& stats);

}  // namespace lc::client
