#pragma once
// Points on a scene's surfaces for the surface light layout (scene_generator.h):
// the triangles whose centroid lies in a box, drawn area-weighted, where no
// alpha mask cuts them out. Double precision, deterministic for a given mixer.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lightcuts/alpha_mask.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"
#include "lightcuts/seeded_mixer.h"

namespace lc::client {

// A triangle the surface layout may place lights on, in double precision.
struct SurfaceTriangle {
    glm::dvec3 a, b, c;
    glm::dvec3 front;  // unit geometric normal, turned to the side the shading normal faces
    int32_t mask = -1;  // alpha mask (SurfaceSelection::masks) cutting it out in places
    glm::vec2 uv[3]{};  // with a mask
};

struct SurfaceSelection {
    std::vector<SurfaceTriangle> triangles;
    std::vector<double> cumulative_area;  // prefix sums of the areas, for area-weighted picks
    double scene_diagonal = 0.0;          // of every mesh, inside the box or not
    size_t usable_triangles = 0;          // non-degenerate ones anywhere in the scene
    std::vector<AlphaMask> masks;         // of alphaMode MASK materials (alpha_mask.h)
};

struct SurfacePoint {
    const SurfaceTriangle* triangle = nullptr;
    glm::dvec3 position{0.0};
};

// The non-degenerate triangles whose centroid lies in [lo, hi] (inclusive).
Result<SurfaceSelection> select_surfaces(const Scene& scene, const glm::dvec3& lo, const glm::dvec3& hi);

// A point uniform over the selected area that no alpha mask cuts out:
// three draws per try whatever the light's type, so positions do not depend
// on types; a scene without masks takes the first try.
Result<SurfacePoint> draw_kept_point(const SurfaceSelection& selection, SplitMix64& rng);

}  // namespace lc::client
