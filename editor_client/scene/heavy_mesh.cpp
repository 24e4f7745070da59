#include "editor_client/scene/heavy_mesh.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/scene_generator.h"
#include "editor_client/scene/inputs/scene_guid.h"

namespace lc::client {

Mesh make_tessellated_sphere(const glm::vec3& centre, float radius, uint32_t triangles, int material) {
    // 2 * stacks * slices triangles (the poles' quads keep a zero-area half),
    // twice as many slices as stacks.
    const uint32_t stacks = std::max(2u, uint32_t(std::sqrt(double(std::max(triangles, 8u)) / 4.0)));
    const uint32_t slices = 2 * stacks;
    Mesh mesh;
    mesh.material = material;
    const size_t vertices = size_t(stacks + 1) * (slices + 1);
    mesh.positions.reserve(vertices);
    mesh.normals.reserve(vertices);
    mesh.uvs.reserve(vertices);
    for (uint32_t i = 0; i <= stacks; ++i) {
        const double theta = std::numbers::pi * double(i) / stacks;
        for (uint32_t j = 0; j <= slices; ++j) {
            const double phi = 2.0 * std::numbers::pi * double(j) / slices;
            const glm::vec3 n(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                              float(-std::sin(theta) * std::sin(phi)));
            mesh.positions.push_back(centre + radius * n);
            mesh.normals.push_back(n);
            mesh.uvs.emplace_back(float(j) / float(slices), float(i) / float(stacks));
        }
    }
    mesh.indices.reserve(size_t(6) * stacks * slices);
    for (uint32_t i = 0; i < stacks; ++i) {
        for (uint32_t j = 0; j < slices; ++j) {
            const uint32_t a = i * (slices + 1) + j, b = a + slices + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    }
    return mesh;
}

Result<Scene> make_heavy_room_scene(uint32_t triangles) {
    if (triangles > kMaxHeavyTriangles)
        return make_error("too large: " + std::to_string(triangles) + " triangles (at most " +
                          std::to_string(kMaxHeavyTriangles) + ")");
    Scene scene = make_furnished_room_scene();
    const int material = scene.meshes.empty() ? -1 : scene.meshes.back().material;
    scene.meshes.push_back(make_tessellated_sphere({2.5f, 1.0f, 2.0f}, 1.0f, triangles, material));
    update_scene_bounds(scene);
    scene.guid = compute_scene_guid(scene);
    return scene;
}

}  // namespace lc::client
