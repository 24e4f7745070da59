#include "editor_client/commands/render_summary.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "editor_client/render/analysis/indirect_census.h"
#include "editor_client/scene/surface_geometry.h"

namespace lc::client {
namespace {

// The real-time mode's part of the summary line: per frame, over how many.
std::string realtime_summary(const RenderStats& stats) {
    if (stats.realtime.cut == 0) return "";
    char text[200];
    std::snprintf(text, sizeof text, " a frame (mean of %u), %.2f shadow rays a pixel (cut of %u, at most %u)",
                  stats.realtime.frames,
                  double(stats.shadows.rays) / double(std::max<uint64_t>(stats.geometry_pixels, 1)),
                  stats.realtime.cut, realtime_ray_budget(stats.realtime.cut, stats.realtime.rays));
    return text;
}

// GPU reconstruction cuts' part of the summary line: rays, fallbacks, storage.
std::string reconstruction_summary(const RenderStats& stats) {
    if (stats.reconstruction.block == 0) return "";
    char text[200];
    std::snprintf(text, sizeof text,
                  ", reconstruction cuts in %ux%u blocks: %.2f shadow rays a pixel, %llu pixels fell back, "
                  "%.1f MiB of records",
                  stats.reconstruction.block, stats.reconstruction.block,
                  double(stats.shadows.rays) / double(std::max<uint64_t>(stats.geometry_pixels, 1)),
                  (unsigned long long)stats.reconstruction.fallbacks,
                  double(stats.reconstruction.bytes) / (1024.0 * 1024.0));
    return text;
}

// Pixels the device's loop limit cut short, said in the summary line too.
std::string loop_limit_summary(const RenderStats& stats) {
    if (stats.cuts.loop_limit_stops == 0) return "";
    return std::to_string(stats.cuts.loop_limit_stops) + " pixels cut short by the device's loop limit, ";
}

}  // namespace

// What the tree's indirect light is, or why there is none, in a line.
void print_indirect_census(const RenderStats& stats, const Scene& scene, const TreeSource& source,
                           const RenderTree& tree) {
    IndirectCensusFacts indirect_facts;
    indirect_facts.has_tree = tree.walk.has_value();
    indirect_facts.vpls = stats.indirect.lights - stats.indirect.patches;
    indirect_facts.patches = stats.indirect.patches;
    // Only a tree with VPLs has a bounce to name.
    if (tree.walk && indirect_facts.vpls > 0) indirect_facts.deepest_vpl_bounce = tree.deepest_vpl_bounce;
    indirect_facts.left_out = stats.indirect.mode == "off";
    indirect_facts.clamped_fraction = stats.indirect.clamped_fraction();
    if (source.bake) indirect_facts.baked = source.bake->indirect;
    // Only a bake that made no indirect light needs to know why.
    if (source.bake && stats.indirect.lights == 0)
        indirect_facts.scene_has_geometry = !extract_surface_geometry(scene).triangles.empty();
    if (std::string census = indirect_census(indirect_facts); !census.empty())
        std::printf("indirect: %s\n", census.c_str());
}

// The loop limit's and the heap's shortfalls, the error against the reference, and the summary line.
void print_report(const RenderStats& stats, const RenderOptions& options, const RenderRequest& request,
                  double command_ms) {
    if (stats.cuts.heap_capacity > 0 && stats.cuts.heap_capacity < stats.cuts.max_cut_setting)
        std::printf(
            "heap search: %u entries on this device (its driver refused private memory for "
            "max cut %u); %llu pixels filled the heap\n",
            stats.cuts.heap_capacity, stats.cuts.max_cut_setting, (unsigned long long)stats.cuts.max_cut_hits);
    if (stats.primary == "rays")
        std::printf("G-buffer: primary rays in compute (%.2f ms GPU)\n", stats.timing.gbuffer_ms);
    if (stats.error.measured)
        std::printf(
            "error vs reference (%.0f ms GPU): mean %.4f, p99 %.4f, %.4f of %llu pixels "
            "over %.3f, max %.4f, %llu max-cut hits\n",
            stats.error.reference_ms, stats.error.rel_err_mean, stats.error.rel_err_p99, stats.error.frac_over_error,
            (unsigned long long)stats.error.pixels, request.settings.error_ratio, stats.error.max_err,
            (unsigned long long)stats.cuts.max_cut_hits);
    std::printf(
        "%s: %s %ux%u, %llu lights (%llu in the tree, %llu classic), %llu nodes, render %.2f ms "
        "%s%s, %.2f ms wall (%.0f ms total), avg cut %.2f, max cut %u, %llu non-finite pixels, "
        "%s%u validation messages -> %s\n",
        stats.device.c_str(), stats.mode.c_str(), request.width, request.height,
        (unsigned long long)stats.lights, (unsigned long long)stats.tree_lights,
        (unsigned long long)stats.classic_lights, (unsigned long long)stats.nodes, stats.timing.render_ms,
        stats.timing.render_clock.c_str(), (realtime_summary(stats) + reconstruction_summary(stats)).c_str(),
        stats.timing.wall_ms, command_ms, stats.cuts.avg_cut,
        stats.cuts.max_cut, (unsigned long long)stats.nonfinite_pixels, loop_limit_summary(stats).c_str(),
        stats.validation_messages, options.output.c_str());
}

}  // namespace lc::client
