#include "lightmass_server/indirect/patch_mesh.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "lightmass_server/indirect/surface_sampling.h"
#include "protocol/bake_limits.h"

namespace lc::bake {
namespace {

uint64_t splits_for(const SurfaceTriangle& t, float patch_size) {
    float longest = std::max({glm::length(t.positions[1] - t.positions[0]),
                              glm::length(t.positions[2] - t.positions[1]),
                              glm::length(t.positions[0] - t.positions[2])});
    double k = std::ceil(double(longest) / double(patch_size));
    return uint64_t(std::clamp(k, 1.0, 65536.0));
}

Patch make_patch(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 normal, uint32_t triangle) {
    Patch p;
    p.vertices[0] = a;
    p.vertices[1] = b;
    p.vertices[2] = c;
    p.centre = (a + b + c) / 3.0f;
    p.normal = normal;
    p.area = 0.5f * glm::length(glm::cross(b - a, c - a));
    p.triangle = triangle;
    return p;
}

}  // namespace

uint64_t count_patches(const SceneGeometry& geometry, float patch_size) {
    uint64_t total = 0;
    for (const SurfaceTriangle& t : geometry.triangles) {
        if (is_degenerate(t)) continue;
        uint64_t k = splits_for(t, patch_size);  // at most 2^16: the sum cannot overflow
        total += k * k;
    }
    return total;
}

Status check_patch_count(const SceneGeometry& geometry, float patch_size, size_t max_patches) {
    if (!(patch_size > 0.0f) || !std::isfinite(patch_size)) {
        return make_error("radiosity patch size must be positive and finite, got " +
                          readable_number(patch_size));
    }
    const uint64_t total = count_patches(geometry, patch_size);
    if (total > max_patches) {
        return make_error("too large: radiosity would make " + std::to_string(total) +
                              " patches at patch size " + readable_number(patch_size) +
                              ", more than the limit of " + std::to_string(max_patches) +
                              "; use a larger --patch-size",
                          ErrorKind::kRefused);
    }
    return Ok{};
}

Result<PatchMesh> make_patches(const SceneGeometry& geometry, float patch_size, size_t max_patches,
                               const BakeStop* stop) {
    if (Status count = check_patch_count(geometry, patch_size, max_patches); !count) return count.failure();
    const uint64_t total = count_patches(geometry, patch_size);
    PatchMesh mesh;
    mesh.patches.reserve(total);
    StopPoll stopped(stop);
    for (uint32_t index = 0; index < geometry.triangles.size(); ++index) {
        // A triangle makes at most 2^32 patches but a row at most 2^17: polled per row too.
        if (stopped()) return stop->reason("radiosity");
        const SurfaceTriangle& t = geometry.triangles[index];
        if (is_degenerate(t)) {
            ++mesh.skipped_degenerate;
            continue;
        }
        glm::vec3 n = front_normal(t);
        uint64_t k = splits_for(t, patch_size);
        glm::vec3 du = (t.positions[1] - t.positions[0]) / float(k);
        glm::vec3 dv = (t.positions[2] - t.positions[0]) / float(k);
        auto grid = [&](uint64_t i, uint64_t j) { return t.positions[0] + float(i) * du + float(j) * dv; };
        // Row j holds the upright triangles (i, j) and the inverted ones between them.
        for (uint64_t j = 0; j < k; ++j) {
            if (stopped()) return stop->reason("radiosity");
            for (uint64_t i = 0; i + j < k; ++i) {
                mesh.patches.push_back(make_patch(grid(i, j), grid(i + 1, j), grid(i, j + 1), n, index));
                if (i + j + 1 < k) {
                    mesh.patches.push_back(make_patch(grid(i + 1, j), grid(i + 1, j + 1), grid(i, j + 1), n, index));
                }
            }
        }
    }
    return mesh;
}

}  // namespace lc::bake
