#include "editor_client/scene/surface_sampler.h"

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace lc::client {
namespace {

// Draws at this many points at most for one light before deciding that the
// masks cut out (nearly) every surface in the box.
constexpr int kMaskedDrawLimit = 10000;

}  // namespace

Result<SurfaceSelection> select_surfaces(const Scene& scene, const glm::dvec3& lo,
                                         const glm::dvec3& hi) {
    SurfaceSelection selection;
    glm::dvec3 scene_min(std::numeric_limits<double>::max());
    glm::dvec3 scene_max(std::numeric_limits<double>::lowest());
    double total_area = 0.0;
    const std::vector<int32_t> mesh_mask = mesh_alpha_masks(scene, selection.masks);
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        const bool has_normals = mesh.normals.size() == mesh.positions.size();
        const int32_t mask = mesh.uvs.size() == mesh.positions.size() ? mesh_mask[m] : -1;
        // A surface its mask cuts out everywhere is not there to stand on.
        if (mesh_mask[m] >= 0 && mask_cuts_everything(selection.masks[size_t(mesh_mask[m])])) continue;
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            auto what = [&] {
                return "mesh " + std::to_string(m) + ", triangle " + std::to_string(t / 3);
            };
            std::array<glm::dvec3, 3> v;
            glm::dvec3 shading_sum(0.0);
            for (size_t k = 0; k < 3; ++k) {
                const uint32_t index = mesh.indices[t + k];
                if (index >= mesh.positions.size()) {
                    return make_error(what() + " has vertex index " + std::to_string(index) +
                                      " out of range (" + std::to_string(mesh.positions.size()) +
                                      " positions)");
                }
                v[k] = glm::dvec3(mesh.positions[index]);
                if (!std::isfinite(v[k].x) || !std::isfinite(v[k].y) || !std::isfinite(v[k].z)) {
                    return make_error(what() + " has a non-finite vertex position");
                }
                if (has_normals) shading_sum += glm::dvec3(mesh.normals[index]);
                scene_min = glm::min(scene_min, v[k]);
                scene_max = glm::max(scene_max, v[k]);
            }
            const glm::dvec3 cross = glm::cross(v[1] - v[0], v[2] - v[0]);
            const double twice_area = glm::length(cross);
            if (!(twice_area > 0.0) || !std::isfinite(twice_area)) continue;  // degenerate
            ++selection.usable_triangles;
            const glm::dvec3 centroid = (v[0] + v[1] + v[2]) / 3.0;
            if (glm::any(glm::lessThan(centroid, lo)) || glm::any(glm::greaterThan(centroid, hi))) {
                continue;
            }
            glm::dvec3 front = cross / twice_area;
            // Vertex normals say which side the surface shows; without any
            // (or if they cancel out), the winding's side.
            const double side = glm::dot(front, shading_sum);
            if (std::isfinite(side) && side < 0.0) front = -front;
            SurfaceTriangle kept{v[0], v[1], v[2], front};
            if (mask >= 0) {
                kept.mask = mask;
                for (size_t k = 0; k < 3; ++k) kept.uv[k] = mesh.uvs[mesh.indices[t + k]];
            }
            selection.triangles.push_back(kept);
            total_area += 0.5 * twice_area;
            selection.cumulative_area.push_back(total_area);
        }
    }
    if (selection.usable_triangles > 0) {
        selection.scene_diagonal = glm::length(scene_max - scene_min);
    }
    return selection;
}

Result<SurfacePoint> draw_kept_point(const SurfaceSelection& selection, SplitMix64& rng) {
    const double total_area = selection.cumulative_area.back();
    for (int attempt = 0; attempt < kMaskedDrawLimit; ++attempt) {
        const double pick = rng.uniform() * total_area;
        const double u1 = rng.uniform();
        const double u2 = rng.uniform();
        const size_t t = std::min(size_t(std::upper_bound(selection.cumulative_area.begin(),
                                                          selection.cumulative_area.end(), pick) -
                                         selection.cumulative_area.begin()),
                                  selection.triangles.size() - 1);
        const SurfaceTriangle& tri = selection.triangles[t];
        // Uniform over the triangle: barycentrics (1 - sqrt(u1), sqrt(u1)(1 - u2), sqrt(u1) u2).
        const double s = std::sqrt(u1);
        const double wa = 1.0 - s, wb = s * (1.0 - u2), wc = s * u2;
        if (tri.mask >= 0) {
            const glm::vec2 uv = tri.uv[0] * float(wa) + tri.uv[1] * float(wb) + tri.uv[2] * float(wc);
            if (!mask_keeps(selection.masks[size_t(tri.mask)], uv)) continue;
        }
        return SurfacePoint{&tri, wa * tri.a + wb * tri.b + wc * tri.c};
    }
    return make_error("the alpha masks cut out (nearly) every surface in the box: no point kept in " +
                      std::to_string(kMaskedDrawLimit) + " draws");
}


}  // namespace lc::client
