#include "lightmass_server/indirect/photon_emitters.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcuts/shading_model.h"
#include "lightmass_server/indirect/surface_sampling.h"

namespace lc::bake {
namespace {

constexpr double kPi = std::numbers::pi;

double mean(glm::dvec3 v) { return (v.x + v.y + v.z) / 3.0; }

// A spot's cone holds at most 2 pi (1 - cos_outer) sr of its intensity.
double cone_solid_angle(const SceneLight& light) {
    return 2.0 * kPi * (1.0 - std::cos(double(light.outer_cone_angle)));
}

}  // namespace

float SceneBounds::extent() const { return glm::length(upper - lower); }

SceneBounds scene_bounds(const SceneGeometry& geometry) {
    SceneBounds b;
    b.lower = glm::vec3(std::numeric_limits<float>::max());
    b.upper = glm::vec3(std::numeric_limits<float>::lowest());
    bool any = false;
    for (const SurfaceTriangle& t : geometry.triangles) {
        if (is_degenerate(t)) continue;
        for (const glm::vec3& p : t.positions) {
            b.lower = glm::min(b.lower, p);
            b.upper = glm::max(b.upper, p);
        }
        any = true;
    }
    return any ? b : SceneBounds{};
}

PhotonEmitters::PhotonEmitters(const SceneGeometry& geometry, std::span<const SceneLight> lights)
    : geometry_(geometry), lights_(lights) {
    SceneBounds bounds = scene_bounds(geometry);
    centre_ = 0.5f * (bounds.lower + bounds.upper);
    radius_ = 0.5f * bounds.extent();

    auto add = [&](bool triangle, uint32_t index, glm::dvec3 power) {
        if (!(mean(power) > 0.0) || !std::isfinite(mean(power))) return;
        sources_.push_back({triangle, index, mean(power)});
        total_power_ += power;
    };
    for (uint32_t i = 0; i < lights.size(); ++i) {
        const SceneLight& light = lights[i];
        glm::dvec3 radiant = glm::dvec3(light.color) * double(light.intensity);
        switch (light.type) {
            case LightType::kPoint: add(false, i, 4.0 * kPi * radiant); break;
            case LightType::kSpot: add(false, i, cone_solid_angle(light) * radiant); break;
            case LightType::kDirectional:
                add(false, i, kPi * double(radius_) * double(radius_) * radiant);
                break;
            case LightType::kOriented: add(false, i, kPi * radiant); break;
        }
    }
    for (uint32_t i = 0; i < geometry.triangles.size(); ++i) {
        const SurfaceTriangle& t = geometry.triangles[i];
        if (t.material >= geometry.materials.size() || is_degenerate(t)) continue;
        // A Lambertian emitter of radiance L_e leaves pi L_e per unit area.
        add(true, i, kPi * double(triangle_area(t)) * glm::dvec3(geometry.materials[t.material].emission));
    }
    double sum = 0.0;
    for (const Source& s : sources_) cdf_.push_back(sum += s.power);
}

Photon PhotonEmitters::sample(const double (&u)[5], uint64_t count) const {
    double pick = u[0] * cdf_.back();
    size_t k = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), pick) - cdf_.begin());
    k = std::min(k, sources_.size() - 1);
    const Source& source = sources_[k];
    // Flux of one photon: the source's radiance over its sampling densities,
    // divided among `count` photons, the source picked with p = power / total.
    double share = cdf_.back() / (source.power * double(count));
    Photon photon;
    if (source.triangle) {
        const SurfaceTriangle& t = geometry_.triangles[source.index];
        glm::vec3 n = front_normal(t);
        photon.origin = uniform_triangle_point(t.positions, u[1], u[2]);
        photon.direction = to_world(tangent_frame(n), cosine_hemisphere(u[3], u[4]));
        // Cosine-weighted directions: L_e cos / (pdf_A pdf_w) = pi A L_e.
        glm::dvec3 emission(geometry_.materials[t.material].emission);
        photon.flux = glm::vec3(kPi * double(triangle_area(t)) * emission * share);
        photon.origin += n * ray_epsilon(2.0f * radius_);
        return photon;
    }
    const SceneLight& light = lights_[source.index];
    glm::dvec3 radiant = glm::dvec3(light.color) * double(light.intensity);
    switch (light.type) {
        case LightType::kPoint:
            photon.origin = light.position;
            photon.direction = uniform_sphere(u[1], u[2]);
            photon.flux = glm::vec3(4.0 * kPi * radiant * share);
            photon.range = light.range;
            break;
        case LightType::kSpot: {
            double cos_outer = std::cos(double(light.outer_cone_angle));
            double cos_inner = std::cos(double(light.inner_cone_angle));
            glm::vec3 axis = glm::normalize(light.direction);
            photon.origin = light.position;
            photon.direction = to_world(tangent_frame(axis), uniform_cone(u[1], u[2], cos_outer));
            double attenuation = shading::spot_attenuation(double(glm::dot(photon.direction, axis)), cos_outer,
                                                           shading::spot_scale(cos_inner, cos_outer));
            photon.flux = glm::vec3(cone_solid_angle(light) * attenuation * radiant * share);
            photon.range = light.range;
            break;
        }
        case LightType::kDirectional: {
            // A uniform point on the disc facing the light, outside the scene's sphere.
            glm::vec3 d = glm::normalize(light.direction);
            TangentFrame frame = tangent_frame(d);
            double r = double(radius_) * std::sqrt(u[1]);
            double phi = 2.0 * kPi * u[2];
            photon.origin = centre_ - d * (1.01f * radius_) + float(r * std::cos(phi)) * frame.t +
                            float(r * std::sin(phi)) * frame.b;
            photon.direction = d;
            photon.flux = glm::vec3(kPi * double(radius_) * double(radius_) * radiant * share);
            break;
        }
        case LightType::kOriented: {
            // A cosine emitter: cosine-weighted directions carry pi I each.
            glm::vec3 n = glm::normalize(light.direction);
            photon.origin = light.position + n * ray_epsilon(2.0f * radius_);
            photon.direction = to_world(tangent_frame(n), cosine_hemisphere(u[1], u[2]));
            photon.flux = glm::vec3(kPi * radiant * share);
            photon.range = light.range;
            break;
        }
    }
    return photon;
}

}  // namespace lc::bake
