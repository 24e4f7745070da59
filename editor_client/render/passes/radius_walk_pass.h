#pragma once
// Lightcuts with the radius criterion: the subgroup walks the tree once,
// refining the nodes whose bounding sphere holds the pixel.
#include "editor_client/render/passes/lightcuts_pass.h"

namespace lc::client {

class RadiusWalkPass final : public LightcutsPass {
public:
    RadiusWalkPass() : LightcutsPass(LightcutsAlgorithm::kRadiusWalk) {}
};

}  // namespace lc::client
