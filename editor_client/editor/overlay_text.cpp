#include "editor_client/editor/overlay_text.h"

#include <cmath>
#include <cstdio>

namespace lc::client {
namespace {

std::string format(const char* pattern, auto... values) {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, pattern, values...);
    return buffer;
}

}  // namespace

std::vector<std::string> overlay_lines(const EditorSession& session, const FrameInfo& frame) {
    std::vector<std::string> lines;
    const ViewState& view = session.view();
    const double fps = frame.frame_ms > 0.0 ? 1000.0 / frame.frame_ms : 0.0;
    const char* reduced = frame.refinement ? " (coarse pass)" : " (moving: reduced)";
    lines.push_back(format("frame %.1f ms (%.1f fps), GPU %.1f ms, %ux%u%s", frame.frame_ms, fps,
                           frame.gpu_ms, frame.width, frame.height, frame.divisor > 1 ? reduced : ""));
    if (const std::optional<RefinementProgress>& r = frame.refinement) {
        if (r->complete())
            lines.push_back(format("refined: %u of %u passes", r->passes, r->passes));
        else if (r->divisor > 1)
            lines.push_back(format("refining: pass %u of %u (1/%u size), %.0f%% of its tiles", r->pass + 1,
                                   r->passes, r->divisor, r->percent));
        else
            lines.push_back(format("refining: pass %u of %u (full size), %.0f%% of its tiles", r->pass + 1,
                                   r->passes, r->percent));
    }
    if (view.mode == RenderMode::kRealtime)
        lines.push_back(format("mode %s, cut of %u, at most %u shadow rays per pixel and frame",
                               render_mode_name(view.mode), view.realtime_cut,
                               realtime_ray_budget(view.realtime_cut, view.realtime_rays)));
    else if (view.mode == RenderMode::kRestir)
        lines.push_back(format("mode %s, %u candidates, %u neighbours, one shadow ray per pixel and frame",
                               render_mode_name(view.mode), view.restir.candidates, view.restir.spatial));
    else
        lines.push_back(format("mode %s, criterion %s, error %.3g, max cut %u",
                               render_mode_name(view.mode), criterion_name(view.criterion),
                               view.error_ratio, view.max_cut));
    if (frame.loop_limit_stops > 0)
        lines.push_back(format("%llu pixels cut short by the device's loop limit",
                               (unsigned long long)frame.loop_limit_stops));
    if (frame.realtime_frames)
        lines.push_back(format("real time: %u frames of this view accumulated", *frame.realtime_frames));
    if (view.representatives != Representatives::kTree)
        lines.push_back(
            format("representatives drawn per pixel: %s", representatives_name(view.representatives)));
    if (frame.avg_cut && frame.max_cut)
        lines.push_back(format("cut size: mean %.1f, max %u", *frame.avg_cut, *frame.max_cut));

    size_t classic = 0;
    for (const SceneLight& light : session.scene().lights) classic += light.classic ? 1 : 0;
    lines.push_back(format("lights %zu (%zu in the tree, %zu classic)",
                           session.scene().lights.size(), session.scene().lights.size() - classic,
                           classic));
    const std::shared_ptr<const LightTree> tree = session.baking().tree();
    if (!tree || tree->empty()) {
        lines.push_back("tree: none (Build lighting to bake one)");
    } else {
        lines.push_back(format("tree: %zu nodes, %u leaves%s", tree->nodes.size(), tree->leaf_count,
                               session.tree_matches_scene() ? "" : " (stale: lights changed)"));
    }
    if (std::optional<BakeProgress> progress = session.baking().bake_progress()) {
        lines.push_back(format("baking: %s %.0f%%",
                               progress->stage.empty() ? "connecting" : progress->stage.c_str(),
                               double(progress->percent)));
    }
    if (const std::optional<BakeReport>& last = session.baking().last_bake()) {
        if (last->succeeded)
            lines.push_back(format("last bake: %.0f ms (build %.0f ms), %zu lights", last->total_ms,
                                   last->build_ms, last->light_count));
        else
            lines.push_back("last bake " + std::string(last->cancelled ? "cancelled" : "failed") +
                            ": " + last->error);
    }
    return lines;
}

}  // namespace lc::client
