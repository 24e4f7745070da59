// editor_client bake SCENE.gltf (--server HOST:PORT | --spawn-server) [...] [-o TREE.lcut] [--json]
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include "editor_client/bake/bake_client.h"
#include "editor_client/commands/bake_options.h"
#include "editor_client/commands/command_errors.h"
#include "editor_client/commands/commands.h"
#include "editor_client/commands/gltf_load_flags.h"
#include "editor_client/report/progress_display.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/inputs/scene_guid.h"
#include "editor_client/scene/surface_geometry.h"

namespace lc::client {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

struct BakeCommandOptions {
    std::string scene;
    GltfLoadOptions gltf;
    BakeFlags bake;
    std::string output;
    bool json = false;
};

// What the summary reports besides the bake's outcome.
struct BakeSummary {
    const Scene& scene;
    const BakeOutcome& outcome;
    std::string builder;      // the builder used
    std::string auto_reason;  // why `auto` chose it (empty: the flag named it)
    double load_ms = 0.0;
    size_t classic_lights = 0;
};

// "8 punctual, 1054763 VPLs": the kinds the tree holds, none when the server did not count them.
std::string tree_light_kinds(const TreeLightCounts& lights) {
    std::string text;
    const std::pair<uint64_t, const char*> kinds[] = {{lights.punctual, "punctual"},
                                                      {lights.area_samples, "area samples"},
                                                      {lights.environment, "environment"},
                                                      {lights.vpls, "VPLs"},
                                                      {lights.patches, "patches"}};
    for (const auto& [count, name] : kinds)
        if (count > 0) text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + name;
    return text;
}

void print_bake_json(const BakeCommandOptions& options, const BakeSummary& summary) {
    const BakeDoneMsg& done = summary.outcome.done;
    nlohmann::json j;
    j["scene"] = options.scene;
    j["scene_guid"] = summary.scene.guid.to_hex();
    j["lights"] = summary.scene.lights.size();  // the scene's, as before (scripts read it)
    const TreeLightCounts& lights = done.lights;
    j["tree_lights"] = {{"total", done.leaf_count},   {"punctual", lights.punctual},
                        {"area_samples", lights.area_samples}, {"environment", lights.environment},
                        {"vpls", lights.vpls},         {"patches", lights.patches}};
    j["classic_lights"] = summary.classic_lights;
    j["builder"] = summary.builder;
    j["builder_choice"] = summary.auto_reason.empty() ? "flag" : summary.auto_reason;
    j["ranks"] = options.bake.ranks;
    j["seed"] = options.bake.seed;
    j["nodes"] = done.node_count;
    j["leaves"] = done.leaf_count;
    j["build_ms"] = done.build_ms;
    j["exact"] = done.exact;
    j["pairing_cost"] = done.pairing_cost;
    j["pairing_lower_bound"] = done.pairing_lower_bound;
    j["upload_ms"] = summary.outcome.upload_ms;
    j["download_ms"] = summary.outcome.download_ms;
    j["total_ms"] = summary.outcome.total_ms;
    j["load_ms"] = summary.load_ms;
    j["write_ms"] = summary.outcome.write_ms;
    j["import_ms"] = summary.outcome.import_ms;
    j["result_channel"] = summary.outcome.result_channel_name;
    j["output"] = options.output;
    j["effects"] = done.effects;
    std::cout << j.dump(2) << "\n";
}

void print_bake_text(const BakeCommandOptions& options, const BakeSummary& summary) {
    const BakeDoneMsg& done = summary.outcome.done;
    const std::string builder_line =
        summary.auto_reason.empty() ? summary.builder : summary.builder + " (" + summary.auto_reason + ")";
    // The tree's leaves are its lights, whatever made them; the server says which kinds.
    std::string kinds = tree_light_kinds(done.lights);
    if (!kinds.empty()) kinds += "; ";
    std::printf("baked %u lights (%s%zu classic kept local) into %u nodes with %s in %.1f ms\n", done.leaf_count,
                kinds.c_str(), summary.classic_lights, done.node_count, builder_line.c_str(), done.build_ms);
    if (summary.builder == "optimal-pair")
        std::printf("pairing: %s, total distance %.6g, lower bound %.6g\n",
                    done.exact ? "exact (proven optimal)" : "approximate", done.pairing_cost,
                    done.pairing_lower_bound);
    std::printf("transfer: upload %.1f ms, download %.1f ms, total %.1f ms\n", summary.outcome.upload_ms,
                summary.outcome.download_ms, summary.outcome.total_ms);
    std::printf("result channel %s\n", summary.outcome.result_channel_name.c_str());
    for (const std::string& effect : done.effects) std::printf("%s\n", effect.c_str());
    if (!options.output.empty()) std::printf("wrote %s\n", options.output.c_str());
}

void run_bake(const BakeCommandOptions& options) {
    std::vector<std::string> warnings;
    const auto load_start = std::chrono::steady_clock::now();
    Result<Scene> scene = load_scene(options.scene, warnings, options.gltf);
    if (!scene) fail(scene.error());
    const double load_ms = ms_since(load_start);
    for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";

    BakeClientOptions bake = options.bake.to_options(*scene);
    std::string auto_reason;
    const std::string builder = options.bake.resolved_builder(*scene, &auto_reason);
    bake.keep_result_channel = false;
    // The tree goes no further than the dump: validated as it arrives, never decoded into nodes.
    bake.decode_tree = false;
    bake.result_dump = options.output;
    bake.geometry = geometry_the_bake_needs(*scene, bake.indirect.method);
    ProgressDisplay progress(stderr);
    bake.on_progress = [&](const ProgressMsg& p) { progress.update(p.stage, p.percent); };
    bake.on_warning = [&](const std::string& w) {
        progress.finish();
        std::cerr << "server warning: " << w << "\n";
    };
    Result<BakeOutcome> outcome = bake_lights(scene->lights, scene->guid, bake);
    progress.finish();
    if (!outcome) fail("bake failed: " + outcome.error());
    size_t classic = 0;
    for (const SceneLight& l : scene->lights) classic += l.classic ? 1 : 0;
    const BakeSummary summary{*scene, *outcome, builder, auto_reason, load_ms, classic};
    if (options.json)
        print_bake_json(options, summary);
    else
        print_bake_text(options, summary);
}

}  // namespace

void register_bake_command(CLI::App& app) {
    auto options = std::make_shared<BakeCommandOptions>();
    CLI::App* cmd = app.add_subcommand("bake", "Bake a scene's light tree on a lightmass_server");
    cmd->add_option("scene", options->scene, "glTF 2.0 scene (.gltf/.glb) with KHR_lights_punctual")->required();
    add_gltf_load_flags(*cmd, options->gltf);
    options->bake.add_to(*cmd, /*server_required=*/true);
    cmd->add_option("-o,--output", options->output, "Write the received result channel as a dump (.lcut)");
    cmd->add_flag("--json", options->json, "Print the summary as JSON");
    cmd->callback([options] { run_bake(*options); });
}

}  // namespace lc::client
