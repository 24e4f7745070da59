#pragma once
// What `render` takes on its command line, and the flags that fill it.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "editor_client/commands/bake_options.h"
#include "editor_client/commands/restir_options.h"
#include "editor_client/commands/gltf_load_flags.h"
#include "editor_client/commands/shared_render_flags.h"
#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/supersampled_render.h"

namespace lc::client {

struct RenderOptions {
    std::string scene;
    GltfLoadOptions gltf;
    std::string tree;
    BakeFlags bake;
    std::optional<RenderMode> mode;  // none: lightcuts with a tree source, else reference
    bool error_view = false;         // --mode error: lightcuts shown as its error against the reference
    CutCriterion criterion = CutCriterion::kBound;
    float error_ratio = 0.02f;
    uint32_t max_cut = kDefaultMaxCut;
    BoundSearch bound_search = BoundSearch::kWalk;
    bool share_cuts = false;
    uint32_t representative_seed = 0;
    SharedRenderFlags shared;  // the real-time budget, representatives, shadows, primary
    std::string sweep_error;  // "0.005,0.01,...": print the error/time table
    std::string sweep_csv;    // and write it here
    std::string sweep_realtime;             // "lc,K8r1,16": the real-time variants side by side
    std::string sweep_blocks;               // "4,8": --sweep-error's reconstruction-cut rows
    std::string sweep_frames = "1,4,16,64";  // measured after these many frames
    uint32_t sweep_path = 32;  // --sweep-realtime's moving camera: frames of its orbit (0: none)
    bool compare_reference = false;
    std::string size = "512x512";
    std::string camera;
    std::optional<int> camera_index;
    std::optional<float> exposure;  // none: automatic
    std::string output;
    std::string float_output;
    bool exr_half = false;  // .exr outputs in half, not float
    std::string stats;
    bool validation = false;
    uint32_t spp = 1;
    SppMethod spp_method = SppMethod::kGpu;
    uint64_t spp_seed = kDefaultSppSeed;
    uint32_t threads = 2;
    uint32_t pixel_stride = 1;
    uint32_t tile_stride = 1;
    std::string reconstruction = "auto";  // a block side, off, or auto (render_request.cpp)
    uint32_t reconstruction_cap = kDefaultReconstructionCap;
    uint32_t frames = 1;
    bool realtime_filter = true;
    RestirFlags restir;
};

// render --mode's name for the error view, besides the renderer's modes.
inline constexpr const char* kErrorViewName = "error";

// Every flag of `render` but the scene, the tree source and --validation.
void add_render_flags(CLI::App& cmd, RenderOptions& options);

}  // namespace lc::client
