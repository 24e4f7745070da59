#pragma once
// A node's glTF mesh -> Scene::meshes: one Scene::Mesh per triangle
// primitive, flattened to world space. Strips and fans become lists; points
// and lines, and primitives without POSITION, are skipped with a warning.
// Normals go through the inverse transpose and are generated (area-weighted)
// where the file has none, one is degenerate or the transform is singular; a
// mirroring transform swaps the winding back. UVs are the set the material's
// textures use, through its KHR_texture_transform; COLOR_0 is clamped to
// [0, 1]; tangents are read or generated for normal-mapped materials only.
// Materials must be read first (gltf_material_reader.h).
#include <tiny_gltf.h>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "editor_client/scene/gltf_diagnostics.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

class GltfMeshReader {
public:
    // All three outlive the reader; meshes are appended to `scene`.
    GltfMeshReader(const tinygltf::Model& model, GltfDiagnostics& diagnostics, Scene& scene)
        : model_(model), diagnostics_(diagnostics), scene_(scene) {}

    // Mesh `mesh_index`, hung from node `node_index` at `world`.
    Status add_mesh(int node_index, int mesh_index, const glm::dmat4& world);

private:
    Status add_primitive(int mesh_index, int primitive_index, const glm::dmat4& world);
    Result<std::vector<uint32_t>> read_triangles(const tinygltf::Primitive& prim, int mode,
                                                 const std::string& what, size_t vertex_count) const;
    Status place_positions(const std::vector<glm::vec3>& positions, const glm::dmat4& world,
                           const std::string& what, Mesh& mesh) const;
    Status read_normals(const tinygltf::Primitive& prim, const std::string& what, const glm::dmat3& linear,
                        Mesh& mesh) const;
    Status read_uvs(const tinygltf::Primitive& prim, const std::string& what, Mesh& mesh);
    Status read_colors(const tinygltf::Primitive& prim, const std::string& what, Mesh& mesh) const;
    Status read_tangents(const tinygltf::Primitive& prim, const std::string& what, const glm::dmat3& linear,
                         Mesh& mesh) const;
    // "mesh 0 primitive 1: NORMAL has 3 elements but POSITION has 4"
    Status check_count(const std::string& what, const std::string& attribute, size_t count,
                       const Mesh& mesh) const;
    const Material* material_of(const tinygltf::Primitive& prim) const;

    const tinygltf::Model& model_;
    GltfDiagnostics& diagnostics_;
    Scene& scene_;
};

}  // namespace lc::client
