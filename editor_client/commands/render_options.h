#pragma once
// What `render` takes on its command line, and the flags that fill it.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "editor_client/commands/bake_options.h"
#include "editor_client/commands/gltf_load_flags.h"
#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/supersampled_render.h"

namespace lc::client {

struct RenderOptions {
    std::string scene;
    GltfLoadOptions gltf;
    std::string tree;
    BakeFlags bake;
    std::string mode;  // empty: lightcuts with a tree source, else reference
    std::string criterion = "bound";
    float error_ratio = 0.02f;
    uint32_t max_cut = kDefaultMaxCut;
    std::string bound_search = "walk";
    bool share_cuts = false;
    std::string representatives = "tree";
    uint32_t representative_seed = 0;
    std::string shadows = "auto";
    std::string primary = "auto";
    std::string sweep_error;  // "0.005,0.01,...": print the error/time table
    std::string sweep_csv;    // and write it here
    std::string sweep_realtime;             // "8,16,32": the real-time mode's table per cut size
    std::string sweep_blocks;               // "4,8": --sweep-error's reconstruction-cut rows
    std::string sweep_frames = "1,4,16,64";  // measured after these many frames
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
    std::string spp_method = "gpu";
    uint64_t spp_seed = kDefaultSppSeed;
    uint32_t threads = 2;
    uint32_t pixel_stride = 1;
    uint32_t tile_stride = 1;
    uint32_t realtime_cut = 16;
    uint32_t realtime_rays = kDefaultRealtimeRays;
    uint32_t reconstruction_block = 0;
    uint32_t reconstruction_cap = kDefaultReconstructionCap;
    uint32_t frames = 1;
    bool realtime_filter = true;
};

// Every flag of `render` but the scene, the tree source and --validation.
void add_render_flags(CLI::App& cmd, RenderOptions& options);

}  // namespace lc::client
