#include "editor_client/render/environment_census.h"

#include <cstdio>
#include <string>

namespace lc::client {

EffectDecision environment_decision(const Environment& environment, const LightTree* tree,
                                    size_t scene_tree_lights) {
    EffectDecision decision;
    decision.name = environment.has_sky() ? "sun and sky" : "environment";
    if (!tree) {
        decision.reason = "no tree source: the server turns it into lights (--server or --spawn-server)";
        return decision;
    }
    const size_t lights = tree->leaf_count > scene_tree_lights ? tree->leaf_count - scene_tree_lights : 0;
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
