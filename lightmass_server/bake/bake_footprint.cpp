#include "lightmass_server/bake/bake_footprint.h"

#include <algorithm>

#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/indirect/patch_mesh.h"
#include "lightmass_server/indirect/surface_sampling.h"
#include "protocol/bake_limits.h"

namespace lc::bake {
namespace {

uint64_t emissive_triangles(const SceneGeometry& geometry) {
    uint64_t count = 0;
    for (const SurfaceTriangle& t : geometry.triangles) {
        if (t.material >= geometry.materials.size()) continue;
        const glm::vec3 e = geometry.materials[t.material].emission;
        if (e.x + e.y + e.z > 0.0f) ++count;
    }
    return count;
}

uint64_t tree_bytes_per_light(const BuildOptions& build) {
    return build.builder == BuilderKind::kAgglomerative ? kAgglomerativeTreeBytesPerLight
                                                        : kTreeBytesPerLight;
}

// The largest level the optimal-pair builder pairs exactly, in nodes.
uint64_t exact_pairing_nodes(const BuildOptions& build, uint64_t tree_lights) {
    if (build.builder != BuilderKind::kOptimalPair || build.pairing == PairingMode::kApproximate) return 0;
    if (build.pairing == PairingMode::kExact) return tree_lights;
    return std::min<uint64_t>(tree_lights, build.exact_pairing_limit);
}

// Lights the environment adds, and its sampler's table.
void add_environment(const BakeInputs& inputs, BakeFootprint& out, uint64_t& largest_part) {
    const Environment& environment = *inputs.environment;
    const uint64_t width = environment.has_sky() ? kSkyRasterWidth : environment.map.width;
    const uint64_t height = environment.has_sky() ? kSkyRasterHeight : environment.map.height;
    // A sky is rasterised first: 12 bytes a texel beside the table.
    const uint64_t table = (width + 1) * (height + 1) * kBytesPerEnvironmentTexel +
                           (environment.has_sky() ? width * height * 12 : 0);
    out.bytes += table;
    if (table > largest_part) largest_part = table, out.largest = "the environment sampler's table";
    out.tree_lights += inputs.environment_lights != 0 ? inputs.environment_lights : kDefaultEnvironmentLights;
}

// The largest albedo channel a bounce meets: how long the roulette keeps paths.
double largest_bounce_albedo(const SceneGeometry& geometry) {
    double largest = 0.0;
    for (const SurfaceMaterial& m : geometry.materials) {
        const glm::vec3 a = bounce_albedo(m);
        largest = std::max({largest, double(a.x), double(a.y), double(a.z)});
    }
    return largest;
}

// Lights the indirect stage adds, and its own structures.
void add_indirect(const BakeInputs& inputs, BakeFootprint& out, uint64_t& largest_part) {
    const IndirectOptions& indirect = inputs.indirect;
    if (!inputs.geometry || inputs.geometry->triangles.empty()) return;
    if (indirect.method == IndirectMethod::kVpl && indirect.vpl.bounces > 0) {
        const uint64_t most = vpl_light_reservation(indirect.vpl.particle_count, indirect.vpl.bounces,
                                                    largest_bounce_albedo(*inputs.geometry));
        out.max_vpls = most;
        out.tree_lights += most;
        const uint64_t part = most * (kBytesPerVpl + tree_bytes_per_light(inputs.build));
        out.bytes += most * kBytesPerVpl;
        if (part > largest_part) largest_part = part, out.largest = "up to " + std::to_string(most) + " VPLs";
    } else if (indirect.method == IndirectMethod::kRadiosity) {
        const uint64_t patches = std::min<uint64_t>(
            count_patches(*inputs.geometry, indirect.radiosity.patch_size), indirect.radiosity.max_patches);
        out.tree_lights += patches;
        const uint64_t part = patches * (kBytesPerPatch + tree_bytes_per_light(inputs.build));
        out.bytes += patches * kBytesPerPatch;
        if (part > largest_part)
            largest_part = part, out.largest = std::to_string(patches) + " radiosity patches";
    }
}

}  // namespace

BakeFootprint estimate_bake_footprint(const BakeInputs& inputs, bool recording) {
    BakeFootprint out;
    uint64_t largest_part = 0;
    out.tree_lights = inputs.lights ? inputs.lights->size() : 0;
    if (inputs.geometry) {
        const SceneGeometry& geometry = *inputs.geometry;
        out.bytes += geometry.triangles.size() * kRayCasterBytesPerTriangle;
        // The caster's copy of the masks and of the masked triangles.
        for (const SurfaceMask& mask : geometry.masks) out.bytes += mask.keep_bits.size() * sizeof(uint32_t);
        out.bytes += geometry.masked_triangles.size() * sizeof(MaskedTriangle);
        const uint64_t emissive = emissive_triangles(geometry);
        if (emissive > 0) out.tree_lights += std::max<uint64_t>(inputs.area_lights, emissive);
    }
    if (inputs.environment) add_environment(inputs, out, largest_part);
    add_indirect(inputs, out, largest_part);
    const uint64_t tree = out.tree_lights * tree_bytes_per_light(inputs.build) +
                          exact_pairing_nodes(inputs.build, out.tree_lights) * kExactPairingBytesPerNode;
    out.bytes += kBakeFixedBytes + tree;
    // A recorded result is encoded whole beside the tree (two nodes a light).
    if (recording) out.bytes += out.tree_lights * 2 * sizeof(LightTreeNode);
    if (tree >= largest_part) out.largest = "a tree of " + std::to_string(out.tree_lights) + " lights";
    return out;
}

std::string megabytes_text(uint64_t bytes) {
    const uint64_t mb = (bytes + (uint64_t{1} << 20) - 1) >> 20;
    const std::string digits = std::to_string(mb);
    std::string grouped;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) grouped += ',';
        grouped += digits[i];
    }
    return grouped + " MB";
}

}  // namespace lc::bake
