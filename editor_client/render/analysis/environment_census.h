#pragma once
// The effects report's line for light from the sky: what the environment or
// sun and sky became in the tree, or why it was skipped.
#include <cstddef>

#include "editor_client/render/analysis/scene_effects.h"
#include "lightcuts/environment.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc::client {

// `tree`: the baked tree (null without a tree source); `scene_directional_lights`:
// the scene's own directional lights in it (non-classic); the tree's other
// directional leaves came from the sky.
EffectDecision environment_decision(const Environment& environment, const WalkTree* tree,
                                    size_t scene_directional_lights);

}  // namespace lc::client
