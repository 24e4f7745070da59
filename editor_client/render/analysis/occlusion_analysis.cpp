#include "editor_client/render/analysis/occlusion_analysis.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lc::client {
namespace {

struct Triangle {
    glm::dvec3 v[3];
    const Mesh* mesh = nullptr;
    const uint32_t* corners = nullptr;  // into mesh->indices
    int32_t mask = -1;                  // alpha mask (OccluderMasks::masks), -1: opaque
    glm::dvec3 normal;  // unit
    double offset = 0.0;
    double distance(const glm::dvec3& x) const { return glm::dot(normal, x) - offset; }
};

// Beyond this many point-plane tests the check is not worth its time: every
// shadow-casting triangle is then kept.
constexpr double kMaxTests = 2e8;

// True when the whole scene lies on one side of t's plane (see the header).
bool bounds_the_scene(const Triangle& t, std::span<const glm::dvec3> vertices,
                      std::span<const glm::vec3> positions, std::span<const glm::vec3> directions,
                      double tolerance) {
    bool below = false, above = false;
    for (const glm::dvec3& v : vertices) {
        const double d = t.distance(v);
        below = below || d < -tolerance;
        above = above || d > tolerance;
        if (below && above) return false;
    }
    // Inner side: where the other vertices are. All of them in the plane:
    // either side may be inner, and the lights decide.
    double side = below ? -1.0 : above ? 1.0 : 0.0;
    for (const glm::vec3& light : positions) {
        const double d = t.distance(glm::dvec3(light));
        if (!(std::abs(d) > tolerance)) return false;  // on the plane: it could graze
        const double light_side = d > 0.0 ? 1.0 : -1.0;
        if (side == 0.0) side = light_side;
        if (light_side != side) return false;
    }
    for (const glm::vec3& direction : directions) {
        // Towards the light is -direction; it must not head to the outer side.
        const double heading = -glm::dot(t.normal, glm::dvec3(direction));
        if (side == 0.0 && heading != 0.0) side = heading > 0.0 ? 1.0 : -1.0;
        if (heading * side < 0.0) return false;
    }
    return true;
}

}  // namespace

OcclusionAnalysis analyse_occlusion(const Scene& scene, std::span<const glm::vec3> light_positions,
                                    std::span<const glm::vec3> light_directions,
                                    bool drop_bounding) {
    OcclusionAnalysis out;
    std::vector<Triangle> triangles;
    std::vector<glm::dvec3> vertices;
    const std::vector<int32_t> mesh_mask = mesh_alpha_masks(scene, out.masks.masks);
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (!casts_shadows(scene, mesh)) continue;
        // A mask that keeps nothing casts no shadow at all.
        if (mesh_mask[m] >= 0 && mask_cuts_everything(out.masks.masks[size_t(mesh_mask[m])])) continue;
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            Triangle t;
            t.mesh = &mesh;
            t.corners = &mesh.indices[i];
            t.mask = mesh_mask[m];
            bool valid = true;
            for (int k = 0; k < 3 && valid; ++k) {
                const uint32_t index = mesh.indices[i + size_t(k)];
                valid = index < mesh.positions.size();
                if (valid) t.v[k] = glm::dvec3(mesh.positions[index]);
            }
            if (!valid) continue;
            const glm::dvec3 n = glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
            const double twice_area = glm::length(n);
            if (!(twice_area > 0.0) || !std::isfinite(twice_area)) continue;  // hides nothing
            t.normal = n / twice_area;
            t.offset = glm::dot(t.normal, t.v[0]);
            triangles.push_back(t);
            vertices.insert(vertices.end(), t.v, t.v + 3);
        }
    }
    out.casting_triangles = triangles.size();
    if (triangles.empty()) {
        out.possible = false;
        out.reason = "no surface casts shadows";
        return out;
    }
    glm::dvec3 lo = vertices.front(), hi = vertices.front();
    for (const glm::dvec3& v : vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const double tolerance = 1e-6 * std::max(glm::length(hi - lo), 1e-12);
    const double tests = double(triangles.size()) *
                         double(vertices.size() + light_positions.size() + light_directions.size());
    const bool affordable = drop_bounding && tests <= kMaxTests;
    for (const Triangle& t : triangles) {
        if (affordable && bounds_the_scene(t, vertices, light_positions, light_directions, tolerance)) {
            ++out.bounding_triangles;
            continue;
        }
        add_occluder_mask(out.masks, out.occluders.size() / 3, *t.mesh, t.corners, t.mask);
        out.occluders.insert(out.occluders.end(), {glm::vec3(t.v[0]), glm::vec3(t.v[1]),
                                                   glm::vec3(t.v[2])});
    }
    if (!out.masks.any()) out.masks.masks.clear();  // no kept triangle uses one
    const size_t kept = out.occluders.size() / 3;
    out.possible = kept > 0;
    const std::string bounding =
        std::to_string(out.bounding_triangles) + " of " + std::to_string(out.casting_triangles) +
        " shadow-casting triangles bound the scene (every light and surface on their inner side)";
    if (!out.possible) {
        out.reason = bounding + ", so none can hide a light";
    } else if (!drop_bounding) {
        out.reason = std::to_string(kept) + " shadow-casting triangles, every one tested";
    } else if (!affordable) {
        out.reason = std::to_string(kept) +
                     " shadow-casting triangles, too many to look for ones that cannot hide a light";
    } else {
        out.reason = std::to_string(kept) + " triangles may hide a light; " + bounding +
                     " and are not tested";
    }
    return out;
}

}  // namespace lc::client
