#pragma once
// A device-local storage buffer made from host bytes: how the renderer's parts
// put their lights, occluders and texels on the GPU.
#include <cstddef>
#include <span>

#include "editor_client/vk/buffer.h"
#include "editor_client/vk/context.h"
#include "lightcuts/result.h"

namespace lc::client {

// Replaces `out` with a buffer holding `bytes` (the frame set must be rewritten).
inline Status upload_storage(const vk::Context& context, vk::Buffer& out, std::span<const std::byte> bytes) {
    Result<vk::Buffer> buffer = vk::Buffer::create_with_data(context.device(), context.command_pool(), bytes,
                                                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!buffer) return make_error(buffer.error());
    out = std::move(buffer).value();
    return Ok{};
}

}  // namespace lc::client
