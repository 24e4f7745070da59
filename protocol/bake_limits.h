#pragma once
// The limits of a BakeRequest's settings (docs/PROTOCOL.md, "Bake request
// limits"), checked by the client before it sends and by the server the
// moment a request arrives, before it waits for a worker: a request outside
// them is refused with a message naming the setting, its value and the limit.
#include <cstdint>
#include <string>

#include "lightcuts/environment.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"
#include "protocol/messages.h"

namespace lc {

// Light paths a VPL bake may trace (a 10^9-path bake is accepted; the
// server's --max-bake-seconds ends it if it runs too long).
inline constexpr uint64_t kMaxVplPaths = uint64_t{1} << 30;  // 1,073,741,824
// Diffuse bounces per path: as deep as SceneLight::bounce records.
inline constexpr uint32_t kMaxBakeBounces = kMaxRecordedBounce;
static_assert(IndirectRequest{}.bounces == kMaxBakeBounces, "VPL paths default to every bounce");
// A VPL path goes on after a bounce with the probability of its surface's
// largest albedo channel (Russian roulette), at most this: a path through
// white surfaces ends after 20 bounces on average, its weight grows instead.
inline constexpr double kVplMaxSurvival = 0.95;
// Lights to reserve for `paths` VPL paths of at most `bounces` bounces
// through surfaces whose largest albedo channel is at most `max_albedo`:
// twice the expected 1 / (1 - survival) per path (the roulette's mean), never
// more than one per bounce, at most kMaxIndirectLights.
uint64_t vpl_light_reservation(uint64_t paths, uint32_t bounces, double max_albedo);
// Indirect lights (VPLs) one bake may deposit; the tracer stops with "too
// large" when the paths leave more.
inline constexpr uint64_t kMaxIndirectLights = uint64_t{1} << 22;  // 4,194,304
// A radiosity patch's target edge, scene units.
inline constexpr float kMinPatchSize = 1e-6f;
inline constexpr float kMaxPatchSize = 1e6f;
// Radiosity patches one bake may make (the patch size decides the count).
inline constexpr uint64_t kMaxRadiosityPatches = uint64_t{1} << 21;  // 2,097,152
// Environment lights one bake may sample.
inline constexpr uint32_t kMaxBakeEnvironmentLights = kMaxEnvironmentLights;

// A number as a person reads it: %g, so 1e-37 is "1e-37", not "0.000000".
std::string readable_number(double value);

// Every setting of `request` that does not depend on its channels (their
// names and contents are checked by the server against what it holds).
// The error names the first setting out of range, its value and the limit.
Status validate_bake_settings(const BakeRequestMsg& request);

}  // namespace lc
