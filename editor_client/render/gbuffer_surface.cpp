#include "editor_client/render/gbuffer_surface.h"

#include "lightcuts/material_model.h"

namespace lc::client {

SurfacePoint gbuffer_surface_point(const GBufferReadback& g, size_t i) {
    SurfacePoint p;
    p.position = {g.position[4 * i], g.position[4 * i + 1], g.position[4 * i + 2]};
    p.normal = {g.normal[4 * i], g.normal[4 * i + 1], g.normal[4 * i + 2]};
    const glm::dvec3 base(g.albedo[4 * i], g.albedo[4 * i + 1], g.albedo[4 * i + 2]);
    const shading::SurfaceMaterial m =
        shading::surface_material(base, g.albedo[4 * i + 3], g.normal[4 * i + 3]);
    p.albedo = m.diffuse;
    p.specular = m.specular;
    p.exponent = m.exponent;
    p.mirror = shading::mirror_direction(p.normal, p.position, glm::dvec3(g.eye));
    return p;
}

}  // namespace lc::client
