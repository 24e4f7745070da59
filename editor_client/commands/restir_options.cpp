#include "editor_client/commands/restir_options.h"

#include "lightcuts/status_macros.h"

namespace lc::client {

void add_restir_options(CLI::App* cmd, RestirFlags* flags) {
    cmd->add_option("--restir-candidates", flags->candidates,
                    "ReSTIR mode: initial candidates drawn per pixel and frame (M)")
        ->check(CLI::Range(1u, kMaxRestirCandidates))
        ->capture_default_str();
    cmd->add_option("--restir-source", flags->source,
                    "ReSTIR mode: where candidates come from: tree (the light tree's draw, intensity x "
                    "geometry at the point) or power (the tree descended by intensity alone)")
        ->check(CLI::IsMember({"tree", "power"}))
        ->capture_default_str();
    cmd->add_option("--restir-spatial", flags->spatial,
                    "ReSTIR mode: neighbours whose reservoirs each pixel merges (k; 0: no spatial reuse)")
        ->check(CLI::Range(0u, kMaxRestirSpatial))
        ->capture_default_str();
    cmd->add_option("--restir-temporal", flags->temporal,
                    "ReSTIR mode: merge the previous frame's reservoir (reprojected)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    cmd->add_option("--restir-bias", flags->bias,
                    "ReSTIR mode: biased (1/M weights) or unbiased (1/Z: only reservoirs that could "
                    "have drawn the survivor count)")
        ->check(CLI::IsMember({"biased", "unbiased"}))
        ->capture_default_str();
    cmd->add_option("--restir-visibility", flags->visibility,
                    "ReSTIR mode: a shadow ray on each pixel's candidate before reuse (on) or only on "
                    "the final survivor (off)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
}

namespace {

Result<bool> parse_on_off(const std::string& text, const char* flag) {
    if (text == "on") return true;
    if (text == "off") return false;
    return make_error(std::string(flag) + " takes on or off, not '" + text + "'");
}

}  // namespace

Result<RestirSettings> restir_settings_from(const RestirFlags& flags) {
    RestirSettings settings;
    settings.candidates = flags.candidates;
    settings.spatial = flags.spatial;
    std::optional<RestirSource> source = parse_restir_source(flags.source);
    if (!source) return make_error("--restir-source takes tree or power, not '" + flags.source + "'");
    settings.source = *source;
    std::optional<RestirBias> bias = parse_restir_bias(flags.bias);
    if (!bias) return make_error("--restir-bias takes biased or unbiased, not '" + flags.bias + "'");
    settings.bias = *bias;
    Result<bool> temporal = parse_on_off(flags.temporal, "--restir-temporal");
    if (!temporal) return make_error(temporal.error());
    settings.temporal = *temporal;
    Result<bool> visibility = parse_on_off(flags.visibility, "--restir-visibility");
    if (!visibility) return make_error(visibility.error());
    settings.candidate_visibility = *visibility;
    LC_RETURN_IF_ERROR(validate(settings));
    return settings;
}

}  // namespace lc::client
