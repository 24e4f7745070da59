#pragma once
// Scenes for the indirect-light tests: closed boxes (furnaces) and a Cornell
// box lit by its ceiling panel, built as SceneGeometry, plus a brute-force
// path-traced reference of a wall's mean reflected radiosity.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "lightcuts/scene_geometry.h"
#include "lightcuts/seeded_mixer.h"
#include "lightmass_server/indirect/indirect_light.h"
#include "lightmass_server/indirect/surface_sampling.h"
#include "lightmass_server/raycast/ray_caster.h"

namespace lc::test {

inline SurfaceTriangle flat_triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material) {
    SurfaceTriangle t;
    t.positions[0] = a;
    t.positions[1] = b;
    t.positions[2] = c;
    glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    t.normals[0] = t.normals[1] = t.normals[2] = n;
    t.material = material;
    return t;
}

// The quad origin + s u + t v, s, t in [0, 1], facing cross(u, v).
inline void add_quad(SceneGeometry& g, glm::vec3 origin, glm::vec3 u, glm::vec3 v, uint32_t material) {
    g.triangles.push_back(flat_triangle(origin, origin + u, origin + u + v, material));
    g.triangles.push_back(flat_triangle(origin, origin + u + v, origin + v, material));
}

// A rough dielectric whose bounces reflect `rho` (bake::bounce_albedo:
// 0.96 base + 0.04), emitting radiance `radiance`.
inline SurfaceMaterial reflecting(float rho, float radiance) {
    return {glm::vec3((rho - 0.04f) / 0.96f), glm::vec3(radiance)};
}

// The box [0, size]^3 with its six faces facing inwards, all of `material`.
inline SceneGeometry closed_box(SurfaceMaterial material, float size = 1.0f) {
    SceneGeometry g;
    g.materials.push_back(material);
    glm::vec3 x(size, 0, 0), y(0, size, 0), z(0, 0, size), o(0.0f);
    add_quad(g, o, z, x, 0);      // floor, facing +y
    add_quad(g, y, x, z, 0);      // ceiling, facing -y
    add_quad(g, o, y, z, 0);      // x = 0, facing +x
    add_quad(g, x, z, y, 0);      // x = size, facing -x
    add_quad(g, o, x, y, 0);      // z = 0, facing +z
    add_quad(g, z, y, x, 0);      // z = size, facing -z
    return g;
}

// The geometry that breaks naive solvers, added to a unit closed box: a
// zero-area triangle, a copy of the floor on top of itself, and a panel
// standing on the floor, touching it along an edge.
inline void add_hard_cases(SceneGeometry& g) {
    g.triangles.push_back(flat_triangle({0.1f, 0.1f, 0.1f}, {0.2f, 0.1f, 0.1f}, {0.3f, 0.1f, 0.1f}, 0));
    g.triangles.push_back(g.triangles[0]);
    g.triangles.push_back(g.triangles[1]);
    add_quad(g, {0.2f, 0.0f, 0.5f}, {0.6f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}, 0);
}

// A unit Cornell box open at z = 1: red wall at x = 0, green at x = 1, white
// floor, back and ceiling; the ceiling's middle is a white panel of radiance
// `panel_radiance` facing down. Walls are triangle pairs, tagged by `Wall`.
enum Wall : int { kFloor, kCeiling, kBack, kRed, kGreen, kWallCount };

struct CornellBox {
    SceneGeometry geometry;
    std::vector<Wall> wall_of_triangle;
};

inline CornellBox cornell_box(float panel_radiance = 10.0f) {
    CornellBox box;
    SceneGeometry& g = box.geometry;
    g.materials = {{glm::vec3(0.73f), glm::vec3(0.0f)},
                   {glm::vec3(0.63f, 0.065f, 0.05f), glm::vec3(0.0f)},
                   {glm::vec3(0.14f, 0.45f, 0.09f), glm::vec3(0.0f)},
                   {glm::vec3(0.73f), glm::vec3(panel_radiance)}};
    auto quad = [&](Wall wall, glm::vec3 o, glm::vec3 u, glm::vec3 v, uint32_t material) {
        add_quad(g, o, u, v, material);
        box.wall_of_triangle.insert(box.wall_of_triangle.end(), 2, wall);
    };
    quad(kFloor, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0);
    quad(kBack, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    quad(kRed, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 1);
    quad(kGreen, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}, 2);
    // The ceiling (y = 1, facing down) as a frame around the panel [0.35, 0.65]^2.
    const float a = 0.35f, b = 0.65f;
    quad(kCeiling, {0, 1, 0}, {1, 0, 0}, {0, 0, a}, 0);
    quad(kCeiling, {0, 1, b}, {1, 0, 0}, {0, 0, 1 - b}, 0);
    quad(kCeiling, {0, 1, a}, {a, 0, 0}, {0, 0, b - a}, 0);
    quad(kCeiling, {b, 1, a}, {1 - b, 0, 0}, {0, 0, b - a}, 0);
    quad(kCeiling, {a, 1, a}, {b - a, 0, 0}, {0, 0, b - a}, 3);
    return box;
}

// Each wall's mean reflected radiosity from lights on it: the power the lights
// carry over the wall's area (an unbiased estimate for photon-deposited lights).
inline std::vector<glm::dvec3> wall_means(const CornellBox& box, const std::vector<bake::IndirectLight>& lights,
                                          const RayCaster& caster) {
    std::vector<double> area(kWallCount, 0.0);
    for (size_t t = 0; t < box.geometry.triangles.size(); ++t) {
        area[box.wall_of_triangle[t]] += triangle_area(box.geometry.triangles[t]);
    }
    std::vector<glm::dvec3> sum(kWallCount, glm::dvec3(0.0));
    for (const bake::IndirectLight& light : lights) {
        // The wall under the light: the first triangle along its normal, from just in front.
        auto hit = caster.intersect(light.position + light.normal * 1e-3f, -light.normal, 0.0f, 1e-2f);
        if (hit) sum[box.wall_of_triangle[hit->triangle]] += glm::dvec3(light.power);
    }
    for (int w = 0; w < kWallCount; ++w) sum[w] /= area[w];
    return sum;
}

// Direct irradiance at x from the emissive triangles, one shadow-tested
// sample uniform over their area: L_e cos_x cos_y A / d^2.
struct EmissiveArea {
    std::vector<uint32_t> triangles;
    std::vector<double> cdf;
};

inline EmissiveArea emissive_area(const SceneGeometry& g) {
    EmissiveArea e;
    double area = 0.0;
    for (uint32_t t = 0; t < g.triangles.size(); ++t) {
        glm::vec3 emission = g.materials[g.triangles[t].material].emission;
        if (emission.x + emission.y + emission.z <= 0.0f) continue;
        e.triangles.push_back(t);
        e.cdf.push_back(area += triangle_area(g.triangles[t]));
    }
    return e;
}

inline uint32_t pick_by_area(const std::vector<uint32_t>& triangles, const std::vector<double>& cdf, double u) {
    size_t k = 0;
    while (k + 1 < cdf.size() && cdf[k] <= u * cdf.back()) ++k;
    return triangles[k];
}

inline glm::dvec3 direct_irradiance(const SceneGeometry& g, const EmissiveArea& e, const RayCaster& caster,
                                    glm::vec3 x, glm::vec3 n, SplitMix64& rng) {
    double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    if (e.triangles.empty()) return glm::dvec3(0.0);
    const SurfaceTriangle& light = g.triangles[pick_by_area(e.triangles, e.cdf, u0)];
    glm::vec3 y = bake::uniform_triangle_point(light.positions, u1, u2);
    glm::vec3 ny = bake::front_normal(light);
    glm::vec3 to_light = y - x;
    float d2 = glm::dot(to_light, to_light);
    float d = std::sqrt(d2);
    double cos_x = glm::dot(n, to_light) / d, cos_y = -glm::dot(ny, to_light) / d;
    if (!(cos_x > 0.0 && cos_y > 0.0)) return glm::dvec3(0.0);
    glm::vec3 origin = x + n * 1e-4f;
    if (caster.occluded(origin, (y + ny * 1e-4f) - origin, 0.0f, 1.0f - 1e-4f)) return glm::dvec3(0.0);
    return glm::dvec3(g.materials[light.material].emission) * (cos_x * cos_y * e.cdf.back() / double(d2));
}

// Brute force: at uniform points x0 of each wall, one cosine-sampled path
// each with next-event estimation at every vertex and Russian roulette on the
// albedo: E(x_k) = E_direct(x_k) + rho(x_k+1) E(x_k+1), B_r(x0) = rho(x0) E(x0).
inline std::vector<glm::dvec3> path_traced_wall_means(const CornellBox& box, const RayCaster& caster,
                                                      uint64_t paths_per_wall, uint64_t seed) {
    const SceneGeometry& g = box.geometry;
    EmissiveArea emitters = emissive_area(g);
    std::vector<glm::dvec3> means(kWallCount, glm::dvec3(0.0));
    for (int w = 0; w < kWallCount; ++w) {
        std::vector<uint32_t> triangles;
        std::vector<double> cdf;
        double area = 0.0;
        for (uint32_t t = 0; t < g.triangles.size(); ++t) {
            if (box.wall_of_triangle[t] != Wall(w)) continue;
            triangles.push_back(t);
            cdf.push_back(area += triangle_area(g.triangles[t]));
        }
        SplitMix64 rng(mix64(seed + uint64_t(w)));
        glm::dvec3 sum(0.0);
        for (uint64_t i = 0; i < paths_per_wall; ++i) {
            const SurfaceTriangle& start = g.triangles[pick_by_area(triangles, cdf, rng.uniform())];
            glm::vec3 n = bake::front_normal(start);
            double u1 = rng.uniform(), u2 = rng.uniform();
            glm::vec3 x = bake::uniform_triangle_point(start.positions, u1, u2);
            glm::dvec3 throughput(1.0), irradiance(0.0);
            for (int depth = 0; depth < 256; ++depth) {
                irradiance += throughput * direct_irradiance(g, emitters, caster, x, n, rng);
                glm::vec3 d = bake::to_world(bake::tangent_frame(n), bake::cosine_hemisphere(rng.uniform(), rng.uniform()));
                auto hit = caster.intersect(x + n * 1e-4f, d, 0.0f, std::numeric_limits<float>::infinity());
                if (!hit) break;
                const SurfaceTriangle& t = g.triangles[hit->triangle];
                glm::vec3 hn = bake::front_normal(t);
                if (glm::dot(hn, d) >= 0.0f) break;
                glm::dvec3 albedo(bake::bounce_albedo(g.materials[t.material]));
                double survive = std::max({albedo.x, albedo.y, albedo.z});
                if (!(rng.uniform() < survive)) break;
                throughput *= albedo / survive;
                x = x + d * hit->distance;
                n = hn;
            }
            sum += glm::dvec3(bake::bounce_albedo(g.materials[start.material])) * irradiance;
        }
        means[w] = sum / double(paths_per_wall);
    }
    return means;
}

}  // namespace lc::test
