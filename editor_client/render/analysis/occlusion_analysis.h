#pragma once
// Which surfaces can hide a light from a surface point? Shadow rays test only
// those, and shadows are simulated only when there is one (SPEC §6: the scene
// decides). A shadow-casting triangle is dropped, provably never an occluder,
// when the scene lies on one side of its plane: every vertex of every
// shadow-casting triangle on the closed inner side, every positional light
// strictly inside, and every directional light shining into the inner side.
// A shadow ray then starts inside (on a surface, offset along the normal) and
// ends inside or runs off to infinity without leaving the inner side, so it
// cannot cross the plane, let alone the triangle. The walls, floor and ceiling
// of a room are such triangles: an empty room needs no shadows at all, and a
// furnished one only tests its furniture.
#include <glm/vec3.hpp>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "lightcuts/alpha_mask.h"
#include "lightcuts/scene.h"

namespace lc::client {

struct OcclusionAnalysis {
    bool possible = true;  // some triangle may hide some light
    std::string reason;
    // The triangles that may hide a light, three vertices each (world space).
    std::vector<glm::vec3> occluders;
    // Which of them are alpha-masked, and their masks (lightcuts/alpha_mask.h).
    OccluderMasks masks;
    size_t casting_triangles = 0;   // non-degenerate triangles whose material casts shadows
    size_t bounding_triangles = 0;  // of those, dropped: the scene lies on their inner side
};

// `light_positions`: every positional light that will be shaded (tree leaves
// or scene lights, and classic lights); `light_directions`: the directions
// every directional light travels in. `drop_bounding` false keeps every
// shadow-casting triangle (--shadows on).
OcclusionAnalysis analyse_occlusion(const Scene& scene, std::span<const glm::vec3> light_positions,
                                    std::span<const glm::vec3> light_directions,
                                    bool drop_bounding = true);

}  // namespace lc::client
