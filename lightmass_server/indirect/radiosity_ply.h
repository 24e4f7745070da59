#pragma once
// `lightmass_server --radiosity-out FILE`: the solved patches as an ASCII PLY, three
// vertices per patch (patches share no vertices, so each shows its own flat
// value). Each vertex carries the patch's radiosity B in W/m^2 as floats
// (radiosity_r/g/b, the numbers to inspect) and as 8-bit red/green/blue
// (B / max B with the sRGB curve, what mesh viewers show).
#include <glm/vec3.hpp>

#include <span>
#include <string>

#include "lightcuts/result.h"
#include "lightmass_server/indirect/patch_mesh.h"

namespace lc::bake {

std::string radiosity_ply(std::span<const Patch> patches, std::span<const glm::vec3> radiosity);
Status write_radiosity_ply(const std::string& path, std::span<const Patch> patches,
                           std::span<const glm::vec3> radiosity);

}  // namespace lc::bake
