#include "editor_client/render/render_stats.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace lc::client {

nlohmann::json stats_json(const RenderStats& s) {
    nlohmann::json j;
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
    j["gbuffer_ms"] = s.gbuffer_ms;
    j["lighting_ms"] = s.lighting_ms;
    j["output_ms"] = s.output_ms;
    j["wall_ms"] = s.wall_ms;
    j["avg_cut"] = s.avg_cut;
    j["max_cut"] = s.max_cut;
    j["geometry_pixels"] = s.geometry_pixels;
    j["nonfinite_pixels"] = s.nonfinite_pixels;
    j["light_evaluations"] = s.light_evaluations;
    j["effects_simulated"] = effects_json(s.effects_simulated);
    j["effects_skipped"] = effects_json(s.effects_skipped);
    j["validation_messages"] = s.validation_messages;
    j["validation_enabled"] = s.validation_enabled;
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
