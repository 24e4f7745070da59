#pragma once
// Rays against the scene's triangles, cast by Embree (one device and one
// scene per bake). The server's area-light, environment and indirect passes
// all trace through this one class; it is safe to call from many threads
// once built. Alpha-masked triangles (SceneGeometry::masked_triangles) let a
// ray through where their mask cuts the surface out.
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"

namespace lc {

struct RayHit {
    float distance = 0.0f;
    uint32_t triangle = 0;  // index into the SceneGeometry the caster was built from
    float u = 0.0f;         // barycentrics of positions[1] and positions[2]
    float v = 0.0f;
};

class RayCaster {
public:
    // Degenerate triangles are left out (and counted); a geometry made only
    // of them gives a caster that hits nothing. `threads` caps Embree's
    // build threads (0: Embree's choice); hits do not depend on it.
    static Result<RayCaster> build(const SceneGeometry& geometry, int threads = 0);

    RayCaster(RayCaster&&) noexcept;
    RayCaster& operator=(RayCaster&&) noexcept;
    ~RayCaster();

    // The nearest triangle along origin + t * direction, t in (t_min, t_max).
    // `direction` need not be unit; distances are in its units.
    std::optional<RayHit> intersect(glm::vec3 origin, glm::vec3 direction, float t_min,
                                    float t_max) const;
    // Whether any triangle lies along the segment, t in (t_min, t_max).
    bool occluded(glm::vec3 origin, glm::vec3 direction, float t_min, float t_max) const;

    size_t triangle_count() const { return primitive_to_triangle_.size() + masked_to_triangle_.size(); }
    size_t skipped_degenerate() const { return skipped_degenerate_; }

    size_t masked_triangle_count() const { return masked_to_triangle_.size(); }

private:
    struct Embree;
    struct MaskedPrimitives;
    RayCaster() = default;
    Status attach(const SceneGeometry& geometry, const std::vector<uint32_t>& triangles, bool masked);
    std::optional<uint32_t> triangle_of(unsigned geometry_id, unsigned primitive) const;

    std::unique_ptr<Embree> embree_;
    // Embree geometry 0 holds the opaque triangles, geometry 1 the masked ones.
    std::vector<uint32_t> primitive_to_triangle_;
    std::vector<uint32_t> masked_to_triangle_;
    size_t skipped_degenerate_ = 0;
};

}  // namespace lc
