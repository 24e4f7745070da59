#pragma once
// Where the photon tracer's particles come from: every light of the scene
// (points, spots, oriented lights, directional lights from a disc covering
// the scene, and emissive triangles), picked in proportion to power.
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/scene_geometry.h"
#include "lightcuts/scene_light.h"

namespace lc::bake {

struct Photon {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, 1.0f};  // unit
    glm::vec3 flux{0.0f};                   // radiant flux it carries, linear RGB
    float range = 0.0f;                     // punctual light's range window (0: none)
};

// The scene's axis-aligned bounds over non-degenerate triangles.
struct SceneBounds {
    glm::vec3 lower{0.0f};
    glm::vec3 upper{0.0f};
    float extent() const;  // the diagonal's length
};
SceneBounds scene_bounds(const SceneGeometry& geometry);

class PhotonEmitters {
public:
    PhotonEmitters(const SceneGeometry& geometry, std::span<const SceneLight> lights);

    // Total emitted power, linear RGB (W); directional lights count the
    // power that crosses the disc covering the scene.
    glm::dvec3 total_power() const { return total_power_; }
    bool empty() const { return cdf_.empty() || !(cdf_.back() > 0.0); }

    // One of `count` photons carrying total_power() / count between them in
    // expectation, from five uniforms in [0, 1).
    Photon sample(const double (&u)[5], uint64_t count) const;

private:
    struct Source {
        bool triangle;   // an emissive triangle, else a SceneLight
        uint32_t index;  // into the geometry's triangles or the lights
        double power;    // scalar power (mean of RGB), the selection weight
    };

    const SceneGeometry& geometry_;
    std::span<const SceneLight> lights_;
    glm::vec3 centre_{0.0f};
    float radius_ = 0.0f;  // the bounding sphere's, for directional lights
    std::vector<Source> sources_;
    std::vector<double> cdf_;
    glm::dvec3 total_power_{0.0};
};

}  // namespace lc::bake
