#pragma once
// A rectangle of an image's pixels that the compute passes dispatch over
// (vkCmdDispatchBase): the whole image, or one of the progressive editor's
// tiles. Origins are whole workgroups, so the shaders' pixel coordinate
// (gl_GlobalInvocationID) needs no offset of its own.
#include <cstdint>

namespace lc::client {

struct PixelRegion {
    uint32_t x = 0;
    uint32_t y = 0;
    uint32_t width = 0;
    uint32_t height = 0;

    uint64_t pixels() const { return uint64_t(width) * height; }
    bool operator==(const PixelRegion&) const = default;
};

}  // namespace lc::client
