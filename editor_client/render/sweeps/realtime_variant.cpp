#include "editor_client/render/sweeps/realtime_variant.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>

#include "editor_client/render/sweeps/error_sweep.h"
#include "lightcuts/device/limits.h"

namespace lc::client {
namespace {

// The whole of `text` as an unsigned integer in [min, max].
std::optional<uint32_t> parse_whole_count(std::string_view text, uint32_t min, uint32_t max) {
    uint32_t value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < min || value > max)
        return std::nullopt;
    return value;
}

// "", "0.05": deterministic lightcuts at the base's error ratio or this one.
std::optional<RealtimeVariant> lightcuts_variant(std::string_view args, const RenderSettings& base) {
    float ratio = base.error_ratio;
    if (!args.empty()) {
        const auto [end, ec] = std::from_chars(args.data(), args.data() + args.size(), ratio);
        if (ec != std::errc() || end != args.data() + args.size() || !std::isfinite(ratio) || ratio < 0.0f)
            return std::nullopt;
    }
    char label[32];
    std::snprintf(label, sizeof(label), "lc%g", double(ratio));
    return RealtimeVariant{label, RenderMode::kLightcuts, false,
                           [ratio](RenderSettings& s) { s.error_ratio = ratio; }};
}

// "16", "8r1": stochastic lightcuts at K nodes, with the base's ray budget or the one after 'r'.
std::optional<RealtimeVariant> stochastic_variant(std::string_view args, const RenderSettings& base) {
    const size_t r = args.find('r');
    const std::optional<uint32_t> cut = parse_whole_count(args.substr(0, r), 1, kMaxStochasticCut);
    std::optional<uint32_t> rays = base.realtime_rays;
    if (r != std::string_view::npos) rays = parse_whole_count(args.substr(r + 1), 1, kMaxStochasticCut);
    if (!cut || !rays) return std::nullopt;
    std::string label = "K" + std::to_string(*cut);
    if (*rays != 0 && *rays < *cut) label += "r" + std::to_string(*rays);
    return RealtimeVariant{label, RenderMode::kRealtime, true, [cut = *cut, rays = *rays](RenderSettings& s) {
                               s.realtime_cut = cut;
                               s.realtime_rays = rays;
                           }};
}

// "", "16": ReSTIR DI with the base's --restir-* settings, or with this many candidates a pixel.
std::optional<RealtimeVariant> restir_variant(std::string_view args, const RenderSettings& base) {
    std::optional<uint32_t> candidates = base.restir.candidates;
    if (!args.empty()) candidates = parse_whole_count(args, 1, kMaxRestirCandidates);
    if (!candidates) return std::nullopt;
    const std::string label = args.empty() ? "restir" : "restir" + std::to_string(*candidates);
    return RealtimeVariant{label, RenderMode::kRestir, true,
                           [m = *candidates](RenderSettings& s) { s.restir.candidates = m; }};
}

// The kinds of entry, by prefix: a new real-time mode is one more row.
struct VariantKind {
    std::string_view prefix;
    std::optional<RealtimeVariant> (*parse)(std::string_view args, const RenderSettings& base);
};
constexpr VariantKind kVariantKinds[] = {
    {"lc", lightcuts_variant},
    {"K", stochastic_variant},
    {"restir", restir_variant},
};

std::optional<RealtimeVariant> parse_variant(std::string_view item, const RenderSettings& base) {
    if (!item.empty() && item.front() >= '0' && item.front() <= '9') return stochastic_variant(item, base);
    for (const VariantKind& kind : kVariantKinds) {
        if (item.starts_with(kind.prefix)) return kind.parse(item.substr(kind.prefix.size()), base);
    }
    return std::nullopt;
}

}  // namespace

RenderSettings variant_settings(const RealtimeVariant& variant, const RenderSettings& base) {
    RenderSettings settings = base;
    settings.mode = variant.mode;
    if (variant.configure) variant.configure(settings);
    return settings;
}

Result<std::vector<RealtimeVariant>> parse_realtime_variants(std::string_view text, const RenderSettings& base) {
    std::vector<RealtimeVariant> variants;
    for (std::string_view item : split_sweep_list(text)) {
        std::optional<RealtimeVariant> variant = parse_variant(item, base);
        if (!variant)
            return make_error("--sweep-realtime: '" + std::string(item) +
                              "' is not a variant (lc, lc0.05, K16, K8r1 or a cut size such as 16)");
        for (const RealtimeVariant& before : variants) {
            if (before.label == variant->label)
                return make_error("--sweep-realtime: '" + variant->label + "' is listed twice");
        }
        variants.push_back(std::move(*variant));
    }
    return variants;
}

}  // namespace lc::client
