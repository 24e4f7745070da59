#include "editor_client/render/output/render_stats.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace lc::client {

namespace {

// The frame: its scene, lights, mode and size, the pass times.
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
    j["width"] = s.width;
    j["height"] = s.height;
    j["render_ms"] = s.render_ms;
    j["render_clock"] = s.render_clock;
    j["gbuffer_ms"] = s.gbuffer_ms;
    j["primary"] = s.primary;
    j["lighting_ms"] = s.lighting_ms;
    j["output_ms"] = s.output_ms;
    j["wall_ms"] = s.wall_ms;
    j["submissions"] = s.submissions;
    if (s.pixel_stride > 1) j["pixel_stride"] = s.pixel_stride;
    if (s.stride_tile > 1) j["stride_tile"] = s.stride_tile;
    j["exposure"] = s.exposure;
    j["auto_exposure"] = s.auto_exposure;
    j["validation_messages"] = s.validation_messages;
    j["validation_enabled"] = s.validation_enabled;
}

double shadow_rays_per_pixel(const RenderStats& s) {
    return s.geometry_pixels > 0 ? double(s.shadow_rays) / double(s.geometry_pixels) : 0.0;
}

// What the GPU counted: cuts, pixels, evaluations, shadow rays.
void add_counts(const RenderStats& s, nlohmann::json& j) {
    j["avg_cut"] = s.avg_cut;
    j["max_cut"] = s.max_cut;
    j["cut_p99"] = s.cut_p99;
    j["geometry_pixels"] = s.geometry_pixels;
    j["nonfinite_pixels"] = s.nonfinite_pixels;
    j["light_evaluations"] = s.light_evaluations;
    j["effects_simulated"] = effects_json(s.effects_simulated);
    j["effects_skipped"] = effects_json(s.effects_skipped);
    j["max_cut_hits"] = s.max_cut_hits;
    j["loop_limit_stops"] = s.loop_limit_stops;
    j["shadows"] = s.shadows;
    j["shadow_rays"] = s.shadow_rays;
    j["shadow_rays_per_pixel"] = shadow_rays_per_pixel(s);
    j["shadow_triangles"] = s.shadow_triangles;
    j["shadow_bvh_nodes"] = s.shadow_bvh_nodes;
    if (s.reference_dispatches > 0) j["reference_dispatches"] = s.reference_dispatches;
}

void add_indirect(const RenderStats& s, nlohmann::json& j) {
    if (s.indirect.empty()) return;
    j["indirect"] = s.indirect;
    j["indirect_lights"] = s.indirect_lights;
    j["indirect_vpls"] = s.indirect_lights - s.indirect_patches;
    j["indirect_patches"] = s.indirect_patches;
    j["indirect_energy"] = s.indirect_energy;
    j["clamped_energy"] = s.clamped_energy;
    j["clamped_energy_fraction"] = s.clamped_fraction();
    if (s.reference_clamp_passes > 0) {
        j["reference_clamp_passes"] = s.reference_clamp_passes;
        j["reference_visibility_kept"] = s.reference_visibility_kept;
        j["reference_clamp_change"] = s.reference_clamp_change;
    }
}

// The cut search's and the real-time mode's settings, where they apply.
void add_cut_settings(const RenderStats& s, nlohmann::json& j) {
    if (s.max_cut_setting > 0) {
        j["error_ratio"] = s.error_ratio;
        j["max_cut_setting"] = s.max_cut_setting;
        j["bound_search"] = s.bound_search;
        if (s.heap_capacity > 0) j["heap_capacity"] = s.heap_capacity;
        j["representatives"] = s.representatives;
        if (s.representatives == "pixel") j["representative_seed"] = s.representative_seed;
    }
    if (s.realtime_cut > 0) {
        j["realtime_cut"] = s.realtime_cut;
        j["realtime_rays"] = s.realtime_rays;
        j["realtime_frames"] = s.realtime_frames;
    }
    if (s.reconstruction_block > 0) {
        j["reconstruction_block"] = s.reconstruction_block;
        j["reconstruction_cap"] = s.reconstruction_cap;
        j["reconstruction_bytes"] = s.reconstruction_bytes;
        j["reconstruction_fallbacks"] = s.reconstruction_fallbacks;
    }
}

// Against the reference, and the supersampled frame's shading.
void add_error_and_supersampling(const RenderStats& s, nlohmann::json& j) {
    if (s.has_error_stats) {
        j["rel_err_mean"] = s.rel_err_mean;
        j["rel_err_p99"] = s.rel_err_p99;
        j["frac_over_error"] = s.frac_over_error;
        j["max_err"] = s.max_err;
        j["error_pixels"] = s.error_pixels;
        j["reference_ms"] = s.reference_ms;
        j["frac_over_2pct"] = s.frac_over_2pct;
    }
    if (s.spp > 1 || s.spp_method != "gpu") {
        j["spp"] = s.spp;
        j["spp_method"] = s.spp_method;
        j["lightcuts_computed"] = s.lightcuts_computed;
        j["reconstruction_cuts"] = s.reconstruction_cuts;
        if (s.spp_method != "gpu") j["shading_cpu_ms"] = s.shading_cpu_ms;
        if (s.has_error_stats) j["reference_shadow_rays"] = s.reference_shadow_rays;
    }
}

}  // namespace

nlohmann::json stats_json(const RenderStats& s) {
    nlohmann::json j;
    add_frame(s, j);
    add_counts(s, j);
    add_indirect(s, j);
    add_cut_settings(s, j);
    add_error_and_supersampling(s, j);
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
