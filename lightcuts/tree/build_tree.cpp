#include "lightcuts/tree/build_tree.h"

#include <glm/geometric.hpp>

namespace lc {
namespace {

glm::dvec3 to_dvec3(const glm::vec3& v) {
    return glm::dvec3(v.x, v.y, v.z);
}

}  // namespace

BuildNode make_leaf(const SceneLight& light, uint32_t light_index) {
    BuildNode leaf;
    leaf.guid = light.guid;
    leaf.type = light.type;
    leaf.flags.set(kNodeIndirect, light.indirect);
    leaf.flags.set(kNodePatch, light.patch);
    leaf.representative = light_index;
    leaf.min_light_index = light_index;
    leaf.intensity = to_dvec3(light.color) * double(light.intensity);
    leaf.brightness = light.intensity;

    const bool bounded = light.type != LightType::kDirectional && light.range > 0.0f;
    leaf.radius = bounded ? double(light.range) : kUnboundedRadius;

    const glm::dvec3 direction = to_dvec3(light.direction);
    // Directional lights are points on the unit sphere (the paper, section 4).
    const glm::dvec3 point =
        light.type == LightType::kDirectional ? direction : to_dvec3(light.position);
    leaf.bbox_min = point;
    leaf.bbox_max = point;

    // Oriented lights: a cone of the single direction (a spot's own angular
    // falloff is evaluated from its spot cosines); point lights: all directions.
    if (light.type == LightType::kPoint) {
        leaf.cone_axis = glm::dvec3(0.0, 0.0, -1.0);
        leaf.cone_cos = -1.0;
    } else {
        // Float directions are unit length only to ~1e-7; the cone math needs unit axes.
        const double length = glm::length(direction);
        leaf.cone_axis = length > 0.0 ? direction / length : glm::dvec3(0.0, 0.0, -1.0);
        leaf.cone_cos = 1.0;
    }
    return leaf;
}

}  // namespace lc
