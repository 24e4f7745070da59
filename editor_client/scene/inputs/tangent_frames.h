#pragma once
// Tangents for normal maps where the file gives none, in the convention glTF
// names (MikkTSpace's): per vertex, the direction of increasing u in the
// surface, made orthogonal to the vertex normal, with w = +-1 the sign that
// gives the bitangent as cross(normal, tangent) * w: the direction of
// decreasing v (glTF's v runs down the image; the normal map's y up it).
// Triangles add their uv-gradient frames to their corners weighted by area,
// so a mirrored half of a model (u running backwards) gets w = -1.
// This is not the MikkTSpace reference code: vertices are not split where
// frames disagree, which the G-buffer tolerates.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace lc::client {

// One tangent per vertex; vertices no triangle gives a frame to get any unit
// vector orthogonal to their normal, with w = 1.
std::vector<glm::vec4> generate_tangents(const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals,
                                         const std::vector<glm::vec2>& uvs,
                                         const std::vector<uint32_t>& indices);

// Any unit vector orthogonal to unit n.
glm::vec3 any_orthogonal(const glm::vec3& n);

}  // namespace lc::client
