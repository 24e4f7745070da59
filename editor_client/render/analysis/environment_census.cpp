#include "editor_client/render/analysis/environment_census.h"

#include <cstdio>
#include <string>

namespace lc::client {

EffectDecision environment_decision(const Environment& environment, const WalkTree* tree,
                                    size_t scene_directional_lights) {
    EffectDecision decision;
    decision.name = environment.has_sky() ? "sun and sky" : "environment";
    if (!tree) {
        decision.reason = "no tree source: the server turns it into lights (--server or --spawn-server)";
        return decision;
    }
    // The sky's lights are the tree's directional leaves beyond the scene's own
    // (area samples and bounces, also made on the server, are oriented).
    size_t directional = 0;
    for (const GpuLight& leaf : tree->leaves) directional += LightType(leaf.type) == LightType::kDirectional;
    const size_t lights = directional > scene_directional_lights ? directional - scene_directional_lights : 0;
    if (lights == 0) {
        decision.reason = "the tree holds no lights beyond the scene's (baked without it, or it emits no light)";
        return decision;
    }
    decision.simulated = true;
    if (environment.has_sky()) {
        char text[128];
        std::snprintf(text, sizeof(text), "%zu directional lights; sun at %.1f deg elevation, turbidity %.1f", lights,
                      environment.sky->elevation_deg, environment.sky->turbidity);
        decision.reason = text;
    } else {
        decision.reason = std::to_string(environment.map.width) + " x " + std::to_string(environment.map.height) +
                          " map, " + std::to_string(lights) + " lights";
    }
    return decision;
}

}  // namespace lc::client
