#pragma once
// The ReSTIR DI mode's options (RenderMode::kRestir, RestirPass): how many
// candidates each pixel draws and from where, which reuse it does and how
// the reused reservoirs are weighted.
#include <cstdint>
#include <optional>
#include <string_view>

#include "lightcuts/result.h"

namespace lc::client {

// Where the initial candidates come from: the light tree's draw from the
// root (each child by intensity x a geometric estimate at the point, the
// real-time mode's draw) or the same descent by intensity (power) alone.
enum class RestirSource : uint8_t { kTree = 0, kPower = 1 };
// How reused reservoirs combine: 1/M weights (cheap, biased where
// neighbours see other lights) or 1/Z (only reservoirs that could have drawn
// the survivor count: unbiased).
enum class RestirBias : uint8_t { kBiased = 0, kUnbiased = 1 };

const char* restir_source_name(RestirSource source);
std::optional<RestirSource> parse_restir_source(std::string_view text);
const char* restir_bias_name(RestirBias bias);
std::optional<RestirBias> parse_restir_bias(std::string_view text);

inline constexpr uint32_t kMaxRestirCandidates = 64;
inline constexpr uint32_t kMaxRestirSpatial = 8;  // restir_spatial.comp's kMaxSpatial

struct RestirSettings {
    uint32_t candidates = 8;  // M, drawn per pixel and frame
    RestirSource source = RestirSource::kTree;
    uint32_t spatial = 3;  // neighbours merged (k); 0: no spatial reuse
    bool temporal = true;  // merge the previous frame's reservoir
    RestirBias bias = RestirBias::kBiased;
    // A shadow ray on the candidates' survivor before reuse (the paper's
    // visibility reuse): one more ray per pixel (k + 1 more when unbiased).
    bool candidate_visibility = false;

    bool operator==(const RestirSettings&) const = default;
};

// The message names the option (--restir-candidates, --restir-spatial).
Status validate(const RestirSettings& settings);

}  // namespace lc::client
