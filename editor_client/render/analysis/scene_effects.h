#pragma once
// Effects on demand (SPEC §6): the scene is analysed once and every effect the
// shaders can simulate is switched on only when something in the scene calls
// for it (specialization constants), each decision with its reason.
#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

#include "lightcuts/scene.h"
#include "lightcuts/occlusion/shadow_ray.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc::client {

struct EffectDecision {
    std::string name;
    bool simulated = false;
    std::string reason;
};

struct SceneEffects {
    // Specialization constants (shaders/effects.glsl).
    bool point_lights = false;
    bool spot_lights = false;
    bool directional_lights = false;
    bool oriented_lights = false;  // cosine emitters: area-light samples
    bool range_window = false;
    bool textures = false;
    bool classic_lights = false;
    bool emissive = false;
    bool shadows = false;  // shadow rays (visibility) for tree and classic lights
    bool specular = false;  // the glossy lobe (material_model.h)
    // The tree's indirect lights (bake --indirect): clamped, or left out.
    bool indirect_clamp = false;
    bool indirect_off = false;
    uint64_t indirect_lights = 0;  // indirect leaves of the tree
    uint64_t indirect_patches = 0;  // of them, radiosity patches (the others are VPLs)
    // What shadow rays test: three vertices per triangle (occlusion_analysis.h).
    std::vector<glm::vec3> occluders;
    OccluderMasks occluder_masks;  // which occluders are alpha-masked

    std::vector<EffectDecision> decisions;

    std::vector<EffectDecision> simulated() const;
    std::vector<EffectDecision> skipped() const;
};

// `tree` (may be null) holds the tree lights when one was imported; otherwise
// the scene's non-classic lights are what reference mode evaluates. Classic
// lights always come from the scene. `shadows`: auto simulates visibility when
// a surface may hide a light (occlusion_analysis.h); on and off are the user's.
// `indirect`: the tree's indirect lights are clamped (true) or left out.
SceneEffects analyse_scene_effects(const Scene& scene, const WalkTree* tree,
                                   ShadowMode shadows = ShadowMode::kAuto, bool indirect = true);

// [{name, reason}, ...]
nlohmann::json effects_json(const std::vector<EffectDecision>& decisions);

}  // namespace lc::client
