#include "editor_client/render/analysis/indirect_census.h"

#include <algorithm>
#include <cstdio>

namespace lc::client {
namespace {

std::string counted(uint64_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string lights_text(const IndirectCensusFacts& f) {
    if (f.vpls > 0 && f.patches > 0)
        return counted(f.vpls, "VPL", "VPLs") + " and " + counted(f.patches, "patch", "patches");
    return f.patches > 0 ? counted(f.patches, "patch", "patches") : counted(f.vpls, "VPL", "VPLs");
}

// Progressive radiosity shoots until the unshot power is below the tolerance:
// every bounce, not a count.
std::string bounces_text(const IndirectCensusFacts& f) {
    if (f.vpls == 0) return "all bounces";
    if (f.baked && f.baked->method == IndirectMethod::kVpl)
        return counted(f.baked->bounces, "bounce", "bounces");
    // Russian roulette may end every path before the requested count: the
    // tree knows the deepest bounce that left a light, not the request.
    if (f.deepest_vpl_bounce > 0) return "up to " + counted(f.deepest_vpl_bounce, "bounce", "bounces");
    return "bounces not recorded in the tree (an older server), see the bake's census";
}

std::string skipped_reason(const IndirectCensusFacts& f) {
    if (!f.baked) return "the tree holds no indirect light (bake --indirect vpl|radiosity)";
    const bool no_bounce = f.baked->method == IndirectMethod::kOff ||
                           (f.baked->method == IndirectMethod::kVpl && f.baked->bounces == 0);
    if (no_bounce) return "no bounce requested";
    if (!f.scene_has_geometry) return "the scene has no geometry";
    return "the bake made no indirect light (no surface reflects the scene's light)";
}

}  // namespace

uint32_t deepest_vpl_bounce(const LightTree& tree) {
    uint32_t deepest = 0;
    for (const LightTreeNode& node : tree.nodes)
        if (node.flags.indirect() && !node.flags.patch() && node.is_leaf())
            deepest = std::max<uint32_t>(deepest, node.bounce);
    return deepest;
}

std::string indirect_census(const IndirectCensusFacts& f) {
    if (!f.has_tree) return "";
    if (f.vpls == 0 && f.patches == 0) return "skipped: " + skipped_reason(f);
    if (f.left_out) return "skipped (--indirect off: " + lights_text(f) + " of the tree left out)";
    char clamped[48];
    std::snprintf(clamped, sizeof clamped, "clamped energy %.3g%%", 100.0 * f.clamped_fraction);
    return "simulated (" + lights_text(f) + ", " + bounces_text(f) + ", " + clamped + ")";
}

}  // namespace lc::client
