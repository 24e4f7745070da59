#include "lightmass_server/indirect/radiosity_ply.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "lightmass_server/control/stale_temporaries.h"

namespace lc::bake {
namespace {

int srgb_byte(float linear) {
    float c = std::clamp(linear, 0.0f, 1.0f);
    float encoded = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return int(std::lround(255.0f * encoded));
}

}  // namespace

std::string radiosity_ply(std::span<const Patch> patches, std::span<const glm::vec3> radiosity) {
    size_t count = std::min(patches.size(), radiosity.size());
    float peak = 0.0f;
    for (size_t i = 0; i < count; ++i) peak = std::max({peak, radiosity[i].x, radiosity[i].y, radiosity[i].z});
    float scale = peak > 0.0f ? 1.0f / peak : 0.0f;
    std::string out = "ply\nformat ascii 1.0\ncomment radiosity per patch, W/m^2 (radiosity_*), sRGB of B / max B\n";
    out += "element vertex " + std::to_string(3 * count) +
           "\nproperty float x\nproperty float y\nproperty float z\n"
           "property float radiosity_r\nproperty float radiosity_g\nproperty float radiosity_b\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    out += "element face " + std::to_string(count) + "\nproperty list uchar int vertex_indices\nend_header\n";
    char line[256];
    for (size_t i = 0; i < count; ++i) {
        const glm::vec3& b = radiosity[i];
        for (const glm::vec3& p : patches[i].vertices) {
            std::snprintf(line, sizeof line, "%.9g %.9g %.9g %.9g %.9g %.9g %d %d %d\n", p.x, p.y, p.z, b.x, b.y, b.z,
                          srgb_byte(b.x * scale), srgb_byte(b.y * scale), srgb_byte(b.z * scale));
            out += line;
        }
    }
    for (size_t i = 0; i < count; ++i) {
        std::snprintf(line, sizeof line, "3 %zu %zu %zu\n", 3 * i, 3 * i + 1, 3 * i + 2);
        out += line;
    }
    return out;
}

Status write_radiosity_ply(const std::string& path, std::span<const Patch> patches,
                           std::span<const glm::vec3> radiosity) {
    // Through a temporary renamed when whole: a crash never leaves half a PLY.
    if (!write_file_whole(path, radiosity_ply(patches, radiosity)))
        return make_error("writing the radiosity PLY " + path + " failed");
    return Ok{};
}

}  // namespace lc::bake
