#pragma once
// The ReSTIR mode's flags, shared by render and view (--mode restir):
// --restir-candidates, --restir-source, --restir-spatial, --restir-temporal,
// --restir-bias and --restir-visibility, each range-checked by CLI11 (its
// message names the flag).
#include <CLI/CLI.hpp>

#include <string>

#include "editor_client/render/settings/restir_settings.h"
#include "lightcuts/result.h"

namespace lc::client {

struct RestirFlags {
    uint32_t candidates = RestirSettings{}.candidates;
    std::string source = restir_source_name(RestirSettings{}.source);
    uint32_t spatial = RestirSettings{}.spatial;
    std::string temporal = RestirSettings{}.temporal ? "on" : "off";
    std::string bias = restir_bias_name(RestirSettings{}.bias);
    std::string visibility = RestirSettings{}.candidate_visibility ? "on" : "off";
};

// Adds the flags to a subcommand, writing into `flags` (which must outlive the parse).
void add_restir_options(CLI::App* cmd, RestirFlags* flags);
// The settings the parsed flags ask for (an error names the flag).
Result<RestirSettings> restir_settings_from(const RestirFlags& flags);

}  // namespace lc::client
