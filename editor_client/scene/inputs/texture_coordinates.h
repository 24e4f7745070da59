#pragma once
// KHR_texture_transform on a texture coordinate: scale, then a rotation
// counter-clockwise in uv (the image turns clockwise), then the offset, as
// the extension's specification composes them.
#include <glm/vec2.hpp>

#include "lightcuts/scene.h"

namespace lc::client {

glm::vec2 transform_uv(const TextureCoordinates& coordinates, glm::vec2 uv);

}  // namespace lc::client
