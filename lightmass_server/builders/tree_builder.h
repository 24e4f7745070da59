#pragma once
// The one entry point every light-tree builder shares.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lightcuts/tree/light_tree.h"
#include "protocol/messages.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/control/bake_stop.h"

namespace lc::bake {

// Above this many nodes in one level, PairingMode::kAuto pairs approximately
// (and says so); kExact still proves optimality, only slower (65,536 lights
// took 6.6 s exact here, 1.1 s approximate; docs/BENCHMARKS.md).
inline constexpr uint32_t kDefaultExactPairingLimit = 32768;

struct BuildOptions {
    BuilderKind builder = BuilderKind::kOptimalPair;
    RepresentativeRule representative_rule = RepresentativeRule::kIntensity;
    PairingMode pairing = PairingMode::kAuto;
    uint32_t exact_pairing_limit = kDefaultExactPairingLimit;
    uint64_t seed = 0;
    // Polled inside the optimal-pair builder's levels (approximate pairing, merges), besides the
    // progress callback between levels; null: never stops.
    const BakeStop* stop = nullptr;
};

// Stage name and percent in [0, 100]; return false to cancel the build.
using ProgressFn = std::function<bool(std::string_view stage, double percent)>;

// One step of a build and its wall-clock time (build_phase_timer.h).
struct BuildPhase {
    std::string name;
    double ms = 0.0;
};

struct BuildReport {
    double build_ms = 0.0;
    // optimal-pair: sum over levels of the chosen pairs' distances, and a lower
    // bound of the optimum (equal to the cost when every level was exact).
    double pairing_cost = 0.0;
    double pairing_lower_bound = 0.0;
    bool exact = true;
    uint32_t levels = 0;
    uint32_t depth = 0;
    std::vector<std::string> warnings;
    // Where build_ms went, step by step, in the order the steps first ran.
    std::vector<BuildPhase> phases;
    // The bake's census (bake_pipeline.h): each effect simulated or skipped, and why.
    std::vector<std::string> effects;
    // The tree's lights by kind, as the bake made them (the builders alone leave it zero).
    TreeLightCounts lights;
};

class ResultChannelFile;  // result_channel_file.h

struct BuildResult {
    LightTree tree;
    BuildReport report;
    // Set, and `tree` left empty, when the tree was built in other processes
    // and stays on disk as the result channel's bytes (a bake over MPI ranks).
    std::shared_ptr<const ResultChannelFile> channel_file;
};

// The per-type trees: one per light type, then one per type of the indirect
// lights (VPLs), then one per type of the radiosity patches. Indirect lights
// never share a cluster with direct ones (so the renderer can clamp or skip
// them by subtree), nor patches with VPLs (patches are not clamped). Direct
// groups come first, so a tree without indirect lights is built as before.
// The groups' trees are joined left to right under junction nodes.
inline constexpr size_t kLightGroupCount = 3 * kLightTypeCount;
size_t light_group(const SceneLight& light);

// Lights must already be validated (protocol/channel_records.h); every light
// given becomes a leaf. Deterministic for equal lights, options and seed.
// A cancelled build returns an error of kind ErrorKind::kCancelled.
Result<BuildResult> build_light_tree(std::span<const SceneLight> lights, const BuildOptions& options,
                                     const ProgressFn& progress);

}  // namespace lc::bake
