#include "editor_client/scene/surface_geometry.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>

#include "lightcuts/alpha_mask.h"
#include "lightcuts/tone_mapping.h"

namespace lc::client {
namespace {

bool valid_texture(const Scene& scene, const Mesh& mesh, int index) {
    return index >= 0 && size_t(index) < scene.textures.size() && !mesh.uvs.empty() &&
           scene.textures[size_t(index)].width > 0 && scene.textures[size_t(index)].height > 0;
}

// The texel under `uv` (repeat wrapping, as the G-buffer's sampler), RGB,
// decoded to linear when the texture holds colour.
glm::vec3 texel(const Texture& texture, glm::vec2 uv) {
    const auto wrap = [](float t, int size) {
        const float f = t - std::floor(t);
        return std::min(size - 1, std::max(0, int(f * float(size))));
    };
    const size_t x = size_t(wrap(uv.x, texture.width));
    const size_t y = size_t(wrap(uv.y, texture.height));
    const uint8_t* p = &texture.rgba8[4 * (y * size_t(texture.width) + x)];
    glm::vec3 c(p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f);
    if (texture.srgb) c = {tone::srgb_decode(c.x), tone::srgb_decode(c.y), tone::srgb_decode(c.z)};
    return c;
}

// The texture's mean over the triangle: stratified barycentric points of an
// n x n grid folded onto the triangle, each read at its nearest texel. The
// mean keeps the triangle's emitted power what the drawn surface shows.
glm::vec3 triangle_mean(const Texture& texture, const glm::vec2 uv[3]) {
    const int n = int(std::lround(std::sqrt(double(kTextureReductionSamples))));
    glm::vec3 sum(0.0f);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            float a = (float(i) + 0.5f) / float(n), b = (float(j) + 0.5f) / float(n);
            if (a + b > 1.0f) {
                a = 1.0f - a;
                b = 1.0f - b;
            }
            sum += texel(texture, uv[0] + a * (uv[1] - uv[0]) + b * (uv[2] - uv[0]));
        }
    }
    return sum / float(n * n);
}

SurfaceMaterial surface_material_of(const Scene& scene, const Mesh& mesh) {
    SurfaceMaterial out;
    if (mesh.material < 0 || size_t(mesh.material) >= scene.materials.size()) {
        out.metallic = 1.0f;  // glTF's default material
        return out;
    }
    const Material& m = scene.materials[size_t(mesh.material)];
    out.base_color = glm::clamp(glm::vec3(m.base_color_factor), 0.0f, 1.0f);
    out.emission = m.emissive_factor;
    out.metallic = glm::clamp(m.metallic, 0.0f, 1.0f);
    out.roughness = glm::clamp(m.roughness, 0.0f, 1.0f);
    return out;
}

// The next triangle is drawn through mask `mask`: its corners' texture
// coordinates, as the client's shadow rays read them (alpha_mask.h).
void add_masked_triangle(SceneGeometry& geometry, const Mesh& mesh, const uint32_t index[3], uint32_t mask) {
    MaskedTriangle t;
    t.triangle = uint32_t(geometry.triangles.size());
    t.mask = mask;
    for (int k = 0; k < 3; ++k) t.uvs[k] = index[k] < mesh.uvs.size() ? mesh.uvs[index[k]] : glm::vec2(0.0f);
    geometry.masked_triangles.push_back(t);
}

// The index of a 1 x 1 mask that keeps nothing, appended the first time.
int32_t see_through_mask(SceneGeometry& geometry) {
    const SurfaceMask none{1, 1, {0u}};
    const auto found = std::find(geometry.masks.begin(), geometry.masks.end(), none);
    if (found != geometry.masks.end()) return int32_t(found - geometry.masks.begin());
    geometry.masks.push_back(none);
    return int32_t(geometry.masks.size() - 1);
}

}  // namespace

SceneGeometry extract_surface_geometry(const Scene& scene) {
    SceneGeometry geometry;
    std::vector<AlphaMask> alpha_masks;
    const std::vector<int32_t> mesh_mask = mesh_alpha_masks(scene, alpha_masks);
    for (const AlphaMask& mask : alpha_masks) geometry.masks.push_back(surface_mask_of(mask));
    for (size_t mesh_index = 0; mesh_index < scene.meshes.size(); ++mesh_index) {
        const Mesh& mesh = scene.meshes[mesh_index];
        if (mesh.indices.size() < 3) continue;
        // Light passes a surface that casts no shadow (BLEND, transmission)
        // on the server as on the client: a mask that keeps nothing.
        const int32_t mask = casts_shadows(scene, mesh) ? mesh_mask[mesh_index] : see_through_mask(geometry);
        const SurfaceMaterial base = surface_material_of(scene, mesh);
        const Material* m = mesh.material >= 0 && size_t(mesh.material) < scene.materials.size()
                                ? &scene.materials[size_t(mesh.material)]
                                : nullptr;
        const bool base_textured = m && valid_texture(scene, mesh, m->base_color_texture);
        const bool emission_textured = m && valid_texture(scene, mesh, m->emissive_texture) &&
                                       glm::any(glm::greaterThan(base.emission, glm::vec3(0.0f)));
        // Untextured meshes share one material; textured ones get one per triangle.
        const uint32_t shared = uint32_t(geometry.materials.size());
        if (!base_textured && !emission_textured) geometry.materials.push_back(base);
        for (size_t k = 0; k + 2 < mesh.indices.size(); k += 3) {
            const uint32_t index[3] = {mesh.indices[k], mesh.indices[k + 1], mesh.indices[k + 2]};
            if (index[0] >= mesh.positions.size() || index[1] >= mesh.positions.size() ||
                index[2] >= mesh.positions.size())
                continue;
            SurfaceTriangle t;
            const bool has_normals = mesh.normals.size() == mesh.positions.size();
            for (int v = 0; v < 3; ++v) {
                t.positions[v] = mesh.positions[index[v]];
                if (has_normals) t.normals[v] = mesh.normals[index[v]];
            }
            // A normal the channel would refuse falls back to the face's.
            const bool unit = has_normals && std::all_of(std::begin(t.normals), std::end(t.normals),
                                                         [](const glm::vec3& n) {
                                                             return std::abs(glm::length(n) - 1.0f) <= 1e-4f;
                                                         });
            if (!unit) {
                const glm::vec3 face = is_degenerate(t) ? glm::vec3(0.0f) : glm::normalize(triangle_cross(t));
                t.normals[0] = t.normals[1] = t.normals[2] = face;
            }
            t.material = shared;
            if (base_textured || emission_textured) {
                const glm::vec2 uv[3] = {mesh.uvs[index[0]], mesh.uvs[index[1]], mesh.uvs[index[2]]};
                SurfaceMaterial own = base;
                if (base_textured)
                    own.base_color *= triangle_mean(scene.textures[size_t(m->base_color_texture)], uv);
                if (emission_textured)
                    own.emission *= triangle_mean(scene.textures[size_t(m->emissive_texture)], uv);
                t.material = uint32_t(geometry.materials.size());
                geometry.materials.push_back(own);
            }
            if (mask >= 0) add_masked_triangle(geometry, mesh, index, uint32_t(mask));
            geometry.triangles.push_back(t);
        }
    }
    return geometry;
}

size_t emissive_triangle_count(const SceneGeometry& geometry) {
    size_t count = 0;
    for (const SurfaceTriangle& t : geometry.triangles) {
        const glm::vec3& e = geometry.materials[t.material].emission;
        if (glm::any(glm::greaterThan(e, glm::vec3(0.0f))) && !is_degenerate(t)) ++count;
    }
    return count;
}

bool emits_power(const SceneGeometry& geometry) { return emissive_triangle_count(geometry) > 0; }

std::shared_ptr<const SceneGeometry> geometry_the_bake_needs(const Scene& scene, IndirectMethod indirect) {
    SceneGeometry geometry = extract_surface_geometry(scene);
    if (!emits_power(geometry) && indirect == IndirectMethod::kOff) return nullptr;
    return std::make_shared<const SceneGeometry>(std::move(geometry));
}

}  // namespace lc::client
