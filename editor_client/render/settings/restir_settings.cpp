#include "editor_client/render/settings/restir_settings.h"

#include <string>

namespace lc::client {

const char* restir_source_name(RestirSource source) {
    switch (source) {
        case RestirSource::kTree:
            return "tree";
        case RestirSource::kPower:
            return "power";
    }
    return "unknown";
}

std::optional<RestirSource> parse_restir_source(std::string_view text) {
    if (text == "tree") return RestirSource::kTree;
    if (text == "power") return RestirSource::kPower;
    return std::nullopt;
}

const char* restir_bias_name(RestirBias bias) {
    switch (bias) {
        case RestirBias::kBiased:
            return "biased";
        case RestirBias::kUnbiased:
            return "unbiased";
    }
    return "unknown";
}

std::optional<RestirBias> parse_restir_bias(std::string_view text) {
    if (text == "biased") return RestirBias::kBiased;
    if (text == "unbiased") return RestirBias::kUnbiased;
    return std::nullopt;
}

Status validate(const RestirSettings& settings) {
    if (settings.candidates < 1 || settings.candidates > kMaxRestirCandidates)
        return make_error("--restir-candidates " + std::to_string(settings.candidates) + " is outside 1 .. " +
                          std::to_string(kMaxRestirCandidates));
    if (settings.spatial > kMaxRestirSpatial)
        return make_error("--restir-spatial " + std::to_string(settings.spatial) + " is outside 0 .. " +
                          std::to_string(kMaxRestirSpatial));
    return Ok{};
}

}  // namespace lc::client
