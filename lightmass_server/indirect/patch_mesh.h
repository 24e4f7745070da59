#pragma once
// The radiosity solver's patches: the scene's triangles, each split into k^2
// similar triangles (k = ceil(longest edge / target size)).
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"
#include "lightmass_server/control/bake_stop.h"

namespace lc::bake {

struct Patch {
    glm::vec3 vertices[3]{};
    glm::vec3 centre{0.0f};
    glm::vec3 normal{0.0f};  // the front side, unit
    float area = 0.0f;
    uint32_t triangle = 0;   // the scene triangle it came from
};

struct PatchMesh {
    std::vector<Patch> patches;
    size_t skipped_degenerate = 0;  // triangles with no area make no patch
};

// Patches make_patches would make.
uint64_t count_patches(const SceneGeometry& geometry, float patch_size);
// The patch size is positive and finite and makes at most `max_patches`; the
// error names the count and the limit ("too large", kRefused).
Status check_patch_count(const SceneGeometry& geometry, float patch_size, size_t max_patches);

// Fails, naming the count, when the patches would exceed `max_patches`; stops
// with `stop`'s reason within a few thousand patches once it is requested
// (two million patches take hundreds of milliseconds).
Result<PatchMesh> make_patches(const SceneGeometry& geometry, float patch_size, size_t max_patches,
                               const BakeStop* stop = nullptr);

}  // namespace lc::bake
