#pragma once
// A heavy scene for measuring what scales with the triangle count (the
// shadow BVH's build, its memory, the .geom upload, the server's Embree
// build, the time per shadow ray): the furnished room with a finely
// tessellated sphere standing on its table's side of the floor.
#include <cstdint>

#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

inline constexpr uint32_t kMaxHeavyTriangles = 1u << 26;

// A UV sphere of about `triangles` triangles (at least 8), with outward
// normals and texture coordinates (u round, v from the top down).
Mesh make_tessellated_sphere(const glm::vec3& centre, float radius, uint32_t triangles, int material);

// The furnished room plus a sphere of about `triangles` triangles (1 m
// radius, on the floor at x = 2.5); refused over kMaxHeavyTriangles.
Result<Scene> make_heavy_room_scene(uint32_t triangles);

}  // namespace lc::client
