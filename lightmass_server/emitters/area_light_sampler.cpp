#include "lightmass_server/emitters/area_light_sampler.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <utility>

#include "lightcuts/guid.h"
#include "lightcuts/seeded_mixer.h"
#include "lightmass_server/indirect/surface_sampling.h"

namespace lc::bake {
namespace {

struct Emitter {
    uint32_t triangle = 0;
    glm::dvec3 power{0.0};
    double weight = 0.0;  // scalar power: the sum of the channels
    uint32_t samples = 0;
};

// Counts proportional to weight summing to `budget` (largest remainders, ties
// to the earlier triangle); a triangle left with none then takes one from the
// triangle with the most, so every emitter keeps its power. budget >= count.
void share_budget(std::vector<Emitter>& emitters, uint64_t budget) {
    const double total = std::accumulate(emitters.begin(), emitters.end(), 0.0,
                                         [](double sum, const Emitter& e) { return sum + e.weight; });
    std::vector<std::pair<double, size_t>> remainders;
    remainders.reserve(emitters.size());
    uint64_t given = 0;
    for (size_t i = 0; i < emitters.size(); ++i) {
        const double share = double(budget) * emitters[i].weight / total;
        const double whole = std::min(std::floor(share), double(budget));
        emitters[i].samples = uint32_t(whole);
        given += uint64_t(whole);
        remainders.emplace_back(share - whole, i);
    }
    std::stable_sort(remainders.begin(), remainders.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (size_t k = 0; given < budget && k < remainders.size(); ++k, ++given)
        ++emitters[remainders[k].second].samples;
    for (Emitter& e : emitters) {
        if (e.samples > 0) continue;
        auto richest = std::max_element(emitters.begin(), emitters.end(),
                                        [](const Emitter& a, const Emitter& b) { return a.samples < b.samples; });
        --richest->samples;
        e.samples = 1;
    }
}

// Van der Corput's radical inverse in base 2: the Hammersley set's second coordinate.
double radical_inverse(uint32_t k) {
    uint32_t bits = k;
    bits = (bits << 16) | (bits >> 16);
    bits = ((bits & 0x00FF00FFu) << 8) | ((bits & 0xFF00FF00u) >> 8);
    bits = ((bits & 0x0F0F0F0Fu) << 4) | ((bits & 0xF0F0F0F0u) >> 4);
    bits = ((bits & 0x33333333u) << 2) | ((bits & 0xCCCCCCCCu) >> 2);
    bits = ((bits & 0x55555555u) << 1) | ((bits & 0xAAAAAAAAu) >> 1);
    return double(bits) * 0x1.0p-32;
}

// The unit square onto the triangle, area-preserving and with little
// distortion (Heitz 2019), so the square's strata stay strata: barycentrics
// of positions[1] and positions[2].
glm::dvec2 square_to_triangle(double u, double v) {
    if (v > u) {
        const double b0 = 0.5 * u;
        return {b0, v - b0};
    }
    const double b1 = 0.5 * v;
    return {u - b1, b1};
}

Guid sample_guid(uint32_t triangle, uint32_t sample) {
    const uint8_t bytes[12] = {'a',
                               'r',
                               'e',
                               'a',
                               uint8_t(triangle),
                               uint8_t(triangle >> 8),
                               uint8_t(triangle >> 16),
                               uint8_t(triangle >> 24),
                               uint8_t(sample),
                               uint8_t(sample >> 8),
                               uint8_t(sample >> 16),
                               uint8_t(sample >> 24)};
    return Guid::from_bytes(bytes);
}

}  // namespace

glm::dvec3 emitted_power(const SceneGeometry& geometry, const SurfaceTriangle& triangle) {
    const double area = 0.5 * glm::length(glm::dvec3(triangle_cross(triangle)));
    return std::numbers::pi * area * glm::dvec3(geometry.materials[triangle.material].emission);
}

Result<AreaLightSampling> sample_area_lights(const SceneGeometry& geometry, uint32_t budget, uint64_t seed,
                                             IndexRange samples, const BakeStop* stop,
                                             std::vector<SceneLight> before) {
    if (budget == 0) return make_error("the area-light budget is 0; give at least 1 sample");
    std::vector<Emitter> emitters;
    for (uint32_t i = 0; i < geometry.triangles.size(); ++i) {
        const SurfaceTriangle& t = geometry.triangles[i];
        if (is_degenerate(t)) continue;
        const glm::dvec3 power = emitted_power(geometry, t);
        if (!(power.x + power.y + power.z > 0.0)) continue;
        if (!std::isfinite(power.x + power.y + power.z))
            return make_error("triangle " + std::to_string(i) + " emits a non-finite power");
        emitters.push_back({i, power, power.x + power.y + power.z, 0});
    }
    AreaLightSampling out;
    out.emissive_triangles = emitters.size();
    if (emitters.empty()) return out;
    out.budget_raised = budget < emitters.size();
    share_budget(emitters, std::max<uint64_t>(budget, emitters.size()));
    // Reserved up front: growing a vector of millions of lights copies it at
    // every doubling, between two stop polls.
    uint64_t total = 0;
    for (const Emitter& e : emitters) total += e.samples;
    out.lights = std::move(before);
    out.lights.reserve(out.lights.size() + std::min(total, samples.end) - std::min(total, samples.begin));

    uint64_t first_sample = 0;  // the index of e's first sample in the whole output
    StopPoll poll(stop);
    for (const Emitter& e : emitters) {
        const uint64_t emitter_first = first_sample;
        first_sample += e.samples;
        if (first_sample <= samples.begin || emitter_first >= samples.end) continue;
        const SurfaceTriangle& t = geometry.triangles[e.triangle];
        const glm::dvec3 p0(t.positions[0]), e1 = glm::dvec3(t.positions[1]) - p0,
                         e2 = glm::dvec3(t.positions[2]) - p0;
        const glm::dvec3 normal = front_normal<double>(t);
        // Radiant intensity along the normal: power / pi shared by the samples.
        const glm::dvec3 intensity = e.power / (std::numbers::pi * double(e.samples));
        const double scale = std::max({intensity.x, intensity.y, intensity.z});
        // A Cranley-Patterson rotation of the Hammersley set, one per triangle.
        SplitMix64 rng(mix64(seed ^ mix64(uint64_t(e.triangle) + kGoldenGamma)));
        const double shift_u = rng.uniform(), shift_v = rng.uniform();
        for (uint32_t k = 0; k < e.samples; ++k) {
            if (!samples.contains(emitter_first + k)) continue;
            if (poll()) return stop->reason("area-light sampling");
            const double u = (double(k) + shift_u) / double(e.samples);
            double v = radical_inverse(k) + shift_v;
            v -= std::floor(v);
            const glm::dvec2 b = square_to_triangle(u, v);
            SceneLight light;
            light.guid = sample_guid(e.triangle, k);
            light.type = LightType::kOriented;
            light.position = glm::vec3(p0 + b.x * e1 + b.y * e2);
            light.direction = glm::vec3(normal);
            light.color = glm::vec3(intensity / scale);
            light.intensity = float(scale);
            out.lights.push_back(light);
        }
    }
    return out;
}

}  // namespace lc::bake
