#include "editor_client/scene/inputs/texture_coordinates.h"

#include <cmath>

namespace lc::client {

glm::vec2 transform_uv(const TextureCoordinates& coordinates, glm::vec2 uv) {
    if (!coordinates.transformed) return uv;
    const double c = std::cos(double(coordinates.rotation));
    const double s = std::sin(double(coordinates.rotation));
    const double x = double(uv.x) * coordinates.scale.x;
    const double y = double(uv.y) * coordinates.scale.y;
    return glm::vec2(float(c * x + s * y + coordinates.offset.x),
                     float(-s * x + c * y + coordinates.offset.y));
}

}  // namespace lc::client
