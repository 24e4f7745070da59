#pragma once
// What a bake will hold in memory at its peak, estimated from the request
// and its stored channels before it starts, so the session can reserve it
// against --memory-budget-mb (or refuse it as "busy" or "too large") instead
// of finding out as the process grows. The per-item costs are the structures'
// sizes times the copies the stages keep alive at once, calibrated against
// the server's measured peak (VmHWM) for every stage at several sizes
// (scripts/fault_test.sh footprint, docs/bench/bake_footprint.csv,
// docs/RELIABILITY.md): an upper bound, by 7-16 % from a million lights up.
// The stored channels are not counted here: their reservations hold them.
#include <cstdint>
#include <string>

#include "lightmass_server/bake/bake_pipeline.h"

namespace lc::bake {

// A light in the tree build, measured at its peak through the server (the
// bake's copy of its lights, the builder's arena and level buffers, the
// exported tree; docs/bench/bake_footprint.csv) and rounded up: 553-572 bytes
// at 1 M and 4 M lights with LBVH and the optimal-pair builder, 594 with the
// agglomerative one.
inline constexpr uint64_t kTreeBytesPerLight = 600;
inline constexpr uint64_t kAgglomerativeTreeBytesPerLight = 640;
// The optimal-pair builder's exact (LEMON) levels: their matching's graph
// and certificate beside the tree, per node of the largest level it pairs
// exactly (32,768 by default; every level with PairingMode::kExact).
inline constexpr uint64_t kExactPairingBytesPerNode = 576;
// What every bake holds whatever its size: its thread's buffers, the
// matching's fixed part, the result stream's frames.
inline constexpr uint64_t kBakeFixedBytes = uint64_t{20} << 20;
// A VPL beside its tree light: the tracer's per-task and merged lists.
inline constexpr uint64_t kBytesPerVpl = 160;
// A radiosity patch beside its tree light: the patch, four double-precision
// colours, and its radiosity and emission in the result.
inline constexpr uint64_t kBytesPerPatch = 256;
// Embree's BVH and our triangle index, per triangle.
inline constexpr uint64_t kRayCasterBytesPerTriangle = 256;
// The environment sampler's summed-area table: a double RGB per texel corner.
inline constexpr uint64_t kBytesPerEnvironmentTexel = 24;
// Below this, with no indirect light, a bake runs on the small-bake lane.
inline constexpr uint64_t kSmallBakeBytes = uint64_t{64} << 20;

struct BakeFootprint {
    uint64_t bytes = 0;        // the estimated peak
    uint64_t tree_lights = 0;  // lights the tree will be built from, at most
    // The VPL tracer's cap: it stops with "too large" beyond this many.
    uint64_t max_vpls = 0;
    // The largest part, for the "too large" message ("VPLs", "tree", ...).
    std::string largest;
};

BakeFootprint estimate_bake_footprint(const BakeInputs& inputs, bool recording);

// "1,234 MB": bytes in whole mebibytes, rounded up.
std::string megabytes_text(uint64_t bytes);

}  // namespace lc::bake
