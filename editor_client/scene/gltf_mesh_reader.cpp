#include "editor_client/scene/gltf_mesh_reader.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "editor_client/scene/gltf_accessor.h"
#include "editor_client/scene/tangent_frames.h"
#include "editor_client/scene/texture_coordinates.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

namespace tg = tinygltf;

// Area-weighted vertex normals: each triangle adds its unnormalised cross
// product (twice its area) to its three vertices.
std::vector<glm::vec3> generate_normals(const std::vector<glm::vec3>& positions,
                                        const std::vector<uint32_t>& indices) {
    std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::dvec3 a(positions[indices[t]]);
        const glm::dvec3 b(positions[indices[t + 1]]);
        const glm::dvec3 c(positions[indices[t + 2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        for (int k = 0; k < 3; ++k) sum[indices[t + size_t(k)]] += n;
    }
    std::vector<glm::vec3> normals(positions.size());
    for (size_t i = 0; i < sum.size(); ++i) {
        const double len = glm::length(sum[i]);
        // A vertex of degenerate triangles only has no normal; any unit vector will do.
        normals[i] = len > 0.0 && std::isfinite(len) ? glm::vec3(sum[i] / len) : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return normals;
}

// Strips and fans become triangle lists with the winding glTF prescribes.
std::vector<uint32_t> triangle_list(const std::vector<uint32_t>& indices, int mode) {
    std::vector<uint32_t> list;
    for (size_t i = 2; i < indices.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            list.insert(list.end(), {indices[0], indices[i - 1], indices[i]});
        } else if (i % 2 == 0) {
            list.insert(list.end(), {indices[i - 2], indices[i - 1], indices[i]});
        } else {
            list.insert(list.end(), {indices[i - 1], indices[i - 2], indices[i]});
        }
    }
    return list;
}

// A mirroring transform flips the winding; swap two corners to keep front
// faces front-facing.
void keep_front_faces(const glm::dmat3& linear, std::vector<uint32_t>& indices) {
    if (!(glm::determinant(linear) < 0.0)) return;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);
}

bool is_triangles(int mode) {
    return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
           mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

// The index of a primitive's attribute, or -1.
int attribute(const tg::Primitive& prim, const std::string& name) {
    auto found = prim.attributes.find(name);
    return found == prim.attributes.end() ? -1 : found->second;
}

}  // namespace

Status GltfMeshReader::add_mesh(int node_index, int mesh_index, const glm::dmat4& world) {
    if (mesh_index >= static_cast<int>(model_.meshes.size())) {
        return diagnostics_.fail("node " + std::to_string(node_index) + " uses mesh " +
                                 std::to_string(mesh_index) + ", which does not exist");
    }
    const tg::Mesh& mesh = model_.meshes[size_t(mesh_index)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        LC_RETURN_IF_ERROR(add_primitive(mesh_index, static_cast<int>(p), world));
    }
    return Ok{};
}

Status GltfMeshReader::add_primitive(int mesh_index, int primitive_index, const glm::dmat4& world) {
    const tg::Primitive& prim = model_.meshes[size_t(mesh_index)].primitives[size_t(primitive_index)];
    const std::string what =
        "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(primitive_index);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (!is_triangles(mode)) {
        diagnostics_.warn(what + " has mode " + std::to_string(mode) +
                          " (points or lines); only triangles are drawn, so it is skipped");
        return Ok{};
    }
    const int position = attribute(prim, "POSITION");
    if (position < 0) {
        diagnostics_.warn(what + " has no POSITION attribute; skipped");
        return Ok{};
    }
    if (prim.material < -1 || prim.material >= static_cast<int>(model_.materials.size())) {
        return diagnostics_.fail(what + " uses material " + std::to_string(prim.material) +
                                 ", which does not exist");
    }
    Result<std::vector<glm::vec3>> positions = read_gltf_vec3(model_, position, what + " POSITION");
    if (!positions) return diagnostics_.fail(positions.error());
    Result<std::vector<uint32_t>> indices = read_triangles(prim, mode, what, positions->size());
    if (!indices) return indices.failure();

    Mesh mesh;
    mesh.material = prim.material;
    LC_RETURN_IF_ERROR(place_positions(*positions, world, what, mesh));
    const glm::dmat3 linear(world);
    keep_front_faces(linear, *indices);
    mesh.indices = std::move(*indices);
    LC_RETURN_IF_ERROR(read_normals(prim, what, linear, mesh));
    LC_RETURN_IF_ERROR(read_uvs(prim, what, mesh));
    LC_RETURN_IF_ERROR(read_colors(prim, what, mesh));
    LC_RETURN_IF_ERROR(read_tangents(prim, what, linear, mesh));
    if (!mesh.indices.empty()) scene_.meshes.push_back(std::move(mesh));
    return Ok{};
}

// The primitive's triangles as a list: its indices, or its vertices in order.
Result<std::vector<uint32_t>> GltfMeshReader::read_triangles(const tg::Primitive& prim, int mode,
                                                             const std::string& what,
                                                             size_t vertex_count) const {
    std::vector<uint32_t> indices;
    if (prim.indices >= 0) {
        Result<std::vector<uint32_t>> read =
            read_gltf_indices(model_, prim.indices, what + " indices", vertex_count);
        if (!read) return diagnostics_.fail(read.error());
        indices = std::move(*read);
    } else {
        if (vertex_count > std::numeric_limits<uint32_t>::max()) {
            return diagnostics_.fail(what + " has too many vertices");
        }
        indices.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) indices[i] = uint32_t(i);
    }
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        return triangle_list(indices, mode);
    }
    if (indices.size() % 3 != 0) {
        return diagnostics_.fail(what + " has " + std::to_string(indices.size()) +
                                 " indices, which is not a multiple of 3");
    }
    return indices;
}

// The positions in world space, each finite.
Status GltfMeshReader::place_positions(const std::vector<glm::vec3>& positions, const glm::dmat4& world,
                                       const std::string& what, Mesh& mesh) const {
    mesh.positions.resize(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        const glm::vec3 p(world * glm::dvec4(glm::dvec3(positions[i]), 1.0));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            return diagnostics_.fail(what + ": vertex " + std::to_string(i) +
                                     " is not finite after the node transform");
        }
        mesh.positions[i] = p;
    }
    return Ok{};
}

Status GltfMeshReader::check_count(const std::string& what, const std::string& attribute, size_t count,
                                   const Mesh& mesh) const {
    if (count == mesh.positions.size()) return Ok{};
    return diagnostics_.fail(what + ": " + attribute + " has " + std::to_string(count) +
                             " elements but POSITION has " + std::to_string(mesh.positions.size()));
}

// NORMAL through the inverse transpose, or generated from the triangles where
// the file has none, a normal is degenerate or the transform is singular.
Status GltfMeshReader::read_normals(const tg::Primitive& prim, const std::string& what,
                                    const glm::dmat3& linear, Mesh& mesh) const {
    const int normal = attribute(prim, "NORMAL");
    const double det = glm::determinant(linear);
    const bool invertible = std::abs(det) > 1e-300 && std::isfinite(det);
    if (normal < 0 || !invertible) {
        mesh.normals = generate_normals(mesh.positions, mesh.indices);
        return Ok{};
    }
    Result<std::vector<glm::vec3>> normals = read_gltf_vec3(model_, normal, what + " NORMAL");
    if (!normals) return diagnostics_.fail(normals.error());
    LC_RETURN_IF_ERROR(check_count(what, "NORMAL", normals->size(), mesh));
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    std::vector<glm::vec3> generated;  // only computed if some normal is degenerate
    mesh.normals.resize(normals->size());
    for (size_t i = 0; i < normals->size(); ++i) {
        const glm::dvec3 n = normal_matrix * glm::dvec3((*normals)[i]);
        const double len = glm::length(n);
        if (len > 1e-20 && std::isfinite(len)) {
            mesh.normals[i] = glm::vec3(n / len);
        } else {
            if (generated.empty()) generated = generate_normals(mesh.positions, mesh.indices);
            mesh.normals[i] = generated[i];
        }
    }
    return Ok{};
}

const Material* GltfMeshReader::material_of(const tg::Primitive& prim) const {
    const bool listed = prim.material >= 0 && size_t(prim.material) < scene_.materials.size();
    return listed ? &scene_.materials[size_t(prim.material)] : nullptr;
}

// The set the material's textures use (TEXCOORD_0 where the asked-for one is
// missing), through its KHR_texture_transform.
Status GltfMeshReader::read_uvs(const tg::Primitive& prim, const std::string& what, Mesh& mesh) {
    const Material* material = material_of(prim);
    const TextureCoordinates coordinates = material ? material->texture_coordinates : TextureCoordinates{};
    std::string name = "TEXCOORD_" + std::to_string(coordinates.set);
    int uv = attribute(prim, name);
    if (uv < 0 && coordinates.set != 0) {
        diagnostics_.warn(what + " has no " + name + " for its material's textures; TEXCOORD_0 is used");
        name = "TEXCOORD_0";
        uv = attribute(prim, name);
    }
    if (uv < 0) return Ok{};
    Result<std::vector<glm::vec2>> uvs = read_gltf_uvs(model_, uv, what + " " + name);
    if (!uvs) return diagnostics_.fail(uvs.error());
    LC_RETURN_IF_ERROR(check_count(what, name, uvs->size(), mesh));
    mesh.uvs = std::move(*uvs);
    if (coordinates.transformed)
        for (glm::vec2& texel : mesh.uvs) texel = transform_uv(coordinates, texel);
    return Ok{};
}

// COLOR_0: VEC3 or VEC4, float or normalized unsigned; alpha 1 for VEC3.
Status GltfMeshReader::read_colors(const tg::Primitive& prim, const std::string& what, Mesh& mesh) const {
    const int color = attribute(prim, "COLOR_0");
    if (color < 0) return Ok{};
    Result<GltfAccessorView> view =
        view_gltf_accessor(model_, color, what + " COLOR_0",
                           "VEC3/VEC4 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT", &is_color);
    if (!view) return diagnostics_.fail(view.error());
    LC_RETURN_IF_ERROR(check_count(what, "COLOR_0", view->count, mesh));
    const int components = view->type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    mesh.colors.assign(view->count, glm::vec4(1.0f));
    for (size_t i = 0; i < view->count; ++i) {
        for (int c = 0; c < components; ++c) {
            const float v = normalized_component(*view, i, c);
            if (!std::isfinite(v))
                return diagnostics_.fail(what + ": COLOR_0 has a non-finite value at element " +
                                         std::to_string(i));
            mesh.colors[i][c] = std::clamp(v, 0.0f, 1.0f);
        }
    }
    return Ok{};
}

// Tangents only for a material with a normal map: the file's TANGENT through
// the node's transform (a mirroring one flips the bitangent's sign), else
// generated (tangent_frames.h).
Status GltfMeshReader::read_tangents(const tg::Primitive& prim, const std::string& what,
                                     const glm::dmat3& linear, Mesh& mesh) const {
    const Material* material = material_of(prim);
    if (!material || material->normal_texture < 0 || mesh.uvs.empty()) return Ok{};
    const int tangent = attribute(prim, "TANGENT");
    if (tangent < 0) {
        mesh.tangents = generate_tangents(mesh.positions, mesh.normals, mesh.uvs, mesh.indices);
        return Ok{};
    }
    Result<std::vector<glm::vec4>> tangents = read_gltf_vec4(model_, tangent, what + " TANGENT");
    if (!tangents) return diagnostics_.fail(tangents.error());
    LC_RETURN_IF_ERROR(check_count(what, "TANGENT", tangents->size(), mesh));
    const float mirror = glm::determinant(linear) < 0.0 ? -1.0f : 1.0f;
    mesh.tangents.resize(tangents->size());
    for (size_t i = 0; i < tangents->size(); ++i) {
        const glm::dvec3 t = linear * glm::dvec3((*tangents)[i]);
        const double length = glm::length(t);
        const float sign = (*tangents)[i].w < 0.0f ? -mirror : mirror;
        mesh.tangents[i] = length > 1e-20 && std::isfinite(length)
                               ? glm::vec4(glm::vec3(t / length), sign)
                               : glm::vec4(any_orthogonal(mesh.normals[i]), sign);
    }
    return Ok{};
}

}  // namespace lc::client
