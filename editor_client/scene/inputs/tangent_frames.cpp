#include "editor_client/scene/inputs/tangent_frames.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace lc::client {
namespace {

struct FrameSum {
    glm::dvec3 tangent{0.0};
    glm::dvec3 bitangent{0.0};
};

// dp/du and dp/dv of one triangle, times twice its uv area's sign-free
// magnitude (so larger triangles weigh more); nothing for a degenerate uv map.
bool triangle_frame(const glm::dvec3 p[3], const glm::dvec2 t[3], FrameSum& out) {
    const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const glm::dvec2 d1 = t[1] - t[0], d2 = t[2] - t[0];
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 1e-20)) return false;
    const double area = glm::length(glm::cross(e1, e2));
    const double scale = area / std::abs(det) / det;  // area weight, 1 / det solve
    out.tangent = (e1 * d2.y - e2 * d1.y) * scale;
    out.bitangent = (e2 * d1.x - e1 * d2.x) * scale;
    return std::isfinite(glm::dot(out.tangent, out.tangent)) &&
           std::isfinite(glm::dot(out.bitangent, out.bitangent));
}

}  // namespace

glm::vec3 any_orthogonal(const glm::vec3& n) {
    const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(axis, n));
}

std::vector<glm::vec4> generate_tangents(const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals,
                                         const std::vector<glm::vec2>& uvs,
                                         const std::vector<uint32_t>& indices) {
    const size_t n = positions.size();
    std::vector<FrameSum> sums(n);
    if (normals.size() == n && uvs.size() == n) {
        for (size_t t = 0; t + 2 < indices.size(); t += 3) {
            glm::dvec3 p[3];
            glm::dvec2 uv[3];
            bool valid = true;
            for (int k = 0; k < 3; ++k) {
                const uint32_t i = indices[t + size_t(k)];
                valid = valid && i < n;
                // glTF's v runs down the image, the tangent frame's y up it.
                if (valid) p[k] = glm::dvec3(positions[i]), uv[k] = glm::dvec2(uvs[i].x, -uvs[i].y);
            }
            FrameSum frame;
            if (!valid || !triangle_frame(p, uv, frame)) continue;
            for (int k = 0; k < 3; ++k) {
                sums[indices[t + size_t(k)]].tangent += frame.tangent;
                sums[indices[t + size_t(k)]].bitangent += frame.bitangent;
            }
        }
    }
    std::vector<glm::vec4> out(n);
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 normal = i < normals.size() ? glm::dvec3(normals[i]) : glm::dvec3(0, 1, 0);
        // Gram-Schmidt: the tangent's part in the surface.
        const glm::dvec3 t = sums[i].tangent - normal * glm::dot(normal, sums[i].tangent);
        const double length = glm::length(t);
        if (!(length > 1e-20) || !std::isfinite(length)) {
            out[i] = glm::vec4(any_orthogonal(glm::vec3(normal)), 1.0f);
            continue;
        }
        const double handedness = glm::dot(glm::cross(normal, t), sums[i].bitangent);
        out[i] = glm::vec4(glm::vec3(t / length), handedness < 0.0 ? -1.0f : 1.0f);
    }
    return out;
}

}  // namespace lc::client
