#include "editor_client/render/output/render_stats.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace lc::client {

namespace {

// The frame: its scene, lights, mode, size, pixels and exposure.
void add_frame(const RenderStats& s, nlohmann::json& j) {
    j["scene"] = s.scene;
    j["device"] = s.device;
    j["lights"] = s.lights;
    j["tree_lights"] = s.tree_lights;
    j["classic_lights"] = s.classic_lights;
    j["nodes"] = s.nodes;
    j["tree_depth"] = s.tree_depth;
    j["mode"] = s.mode;
    j["criterion"] = s.criterion;
    j["primary"] = s.primary;
    j["width"] = s.width;
    j["height"] = s.height;
    j["geometry_pixels"] = s.geometry_pixels;
    j["nonfinite_pixels"] = s.nonfinite_pixels;
    j["effects_simulated"] = effects_json(s.effects_simulated);
    j["effects_skipped"] = effects_json(s.effects_skipped);
    if (s.reference_dispatches > 0) j["reference_dispatches"] = s.reference_dispatches;
    if (s.pixel_stride > 1) j["pixel_stride"] = s.pixel_stride;
    if (s.stride_tile > 1) j["stride_tile"] = s.stride_tile;
    j["exposure"] = s.exposure;
    j["auto_exposure"] = s.auto_exposure;
    j["validation_messages"] = s.validation_messages;
    j["validation_enabled"] = s.validation_enabled;
}

}  // namespace

void FrameTiming::write_json(nlohmann::json& j) const {
    j["render_ms"] = render_ms;
    j["render_clock"] = render_clock;
    j["gbuffer_ms"] = gbuffer_ms;
    j["lighting_ms"] = lighting_ms;
    j["output_ms"] = output_ms;
    j["wall_ms"] = wall_ms;
    j["submissions"] = submissions;
}

void CutStats::write_json(nlohmann::json& j) const {
    j["avg_cut"] = avg_cut;
    j["max_cut"] = max_cut;
    j["cut_p99"] = cut_p99;
    j["light_evaluations"] = light_evaluations;
    j["max_cut_hits"] = max_cut_hits;
    j["loop_limit_stops"] = loop_limit_stops;
    if (max_cut_setting == 0) return;
    j["error_ratio"] = error_ratio;
    j["max_cut_setting"] = max_cut_setting;
    j["bound_search"] = bound_search;
    if (heap_capacity > 0) j["heap_capacity"] = heap_capacity;
    j["representatives"] = representatives;
    if (representatives == "pixel") j["representative_seed"] = representative_seed;
}

void RealtimeStats::write_json(nlohmann::json& j) const {
    if (cut == 0) return;
    j["realtime_cut"] = cut;
    j["realtime_rays"] = rays;
    j["realtime_frames"] = frames;
}

void ReconstructionStats::write_json(nlohmann::json& j) const {
    if (block == 0) return;
    j["reconstruction_block"] = block;
    j["reconstruction_cap"] = cap;
    j["reconstruction_bytes"] = bytes;
    j["reconstruction_fallbacks"] = fallbacks;
}

void ShadowStats::write_json(nlohmann::json& j, uint64_t geometry_pixels) const {
    j["shadows"] = simulated;
    j["shadow_rays"] = rays;
    j["shadow_rays_per_pixel"] = geometry_pixels > 0 ? double(rays) / double(geometry_pixels) : 0.0;
    j["shadow_triangles"] = triangles;
    j["shadow_bvh_nodes"] = bvh_nodes;
}

void IndirectStats::write_json(nlohmann::json& j) const {
    if (mode.empty()) return;
    j["indirect"] = mode;
    j["indirect_lights"] = lights;
    j["indirect_vpls"] = lights - patches;
    j["indirect_patches"] = patches;
    j["indirect_energy"] = energy;
    j["clamped_energy"] = clamped_energy;
    j["clamped_energy_fraction"] = clamped_fraction();
    if (reference_clamp_passes == 0) return;
    j["reference_clamp_passes"] = reference_clamp_passes;
    j["reference_visibility_kept"] = reference_visibility_kept;
    j["reference_clamp_change"] = reference_clamp_change;
}

void ErrorSummary::write_json(nlohmann::json& j, bool supersampled) const {
    if (!measured) return;
    j["rel_err_mean"] = rel_err_mean;
    j["rel_err_p99"] = rel_err_p99;
    j["frac_over_error"] = frac_over_error;
    j["max_err"] = max_err;
    j["error_pixels"] = pixels;
    j["reference_ms"] = reference_ms;
    j["frac_over_2pct"] = frac_over_2pct;
    if (supersampled) j["reference_shadow_rays"] = reference_shadow_rays;
}

void SupersamplingStats::write_json(nlohmann::json& j) const {
    if (!supersampled()) return;
    j["spp"] = spp;
    j["spp_method"] = method;
    j["lightcuts_computed"] = lightcuts_computed;
    j["reconstruction_cuts"] = reconstruction_cuts;
    if (method != "gpu") j["shading_cpu_ms"] = shading_cpu_ms;
}

nlohmann::json stats_json(const RenderStats& s) {
    nlohmann::json j;
    add_frame(s, j);
    s.timing.write_json(j);
    s.cuts.write_json(j);
    s.realtime.write_json(j);
    s.reconstruction.write_json(j);
    s.shadows.write_json(j, s.geometry_pixels);
    s.indirect.write_json(j);
    s.error.write_json(j, s.supersampling.supersampled());
    s.supersampling.write_json(j);
    return j;
}

Status write_stats_json(const std::filesystem::path& path, const RenderStats& stats) {
    std::ofstream out(path);
    if (!out) return make_error("cannot write stats to " + path.string());
    out << stats_json(stats).dump(2) << "\n";
    if (!out.flush()) return make_error("cannot write stats to " + path.string());
    return Ok{};
}

}  // namespace lc::client
