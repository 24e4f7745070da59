#include "editor_client/render/gpu/vpl_visibility.h"

#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

Result<bool> VplVisibility::ensure(const vk::Context& context, uint64_t bytes) {
    if (buffer_ && buffer_.size() >= bytes) return false;
    LC_RETURN_IF_ERROR(context.device().wait_idle());
    Result<vk::Buffer> buffer = vk::Buffer::create(
        context.device(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        vk::MemoryUsage::kDeviceLocal);
    if (!buffer) return make_error("kept visibility: " + buffer.error());
    buffer_ = std::move(buffer).value();
    return true;
}

Result<bool> VplVisibility::prepare(const vk::Context& context, bool clamps, uint32_t leaf_count, uint64_t pixels,
                                    uint64_t budget_bytes) {
    stride_ = 0;
    if (!clamps) return false;
    const uint64_t stride = (uint64_t(leaf_count) + 127) / 128;
    const uint64_t bytes = pixels * stride * sizeof(GpuVisibilityBits);
    if (bytes > budget_bytes) return false;
    Result<bool> remade = ensure(context, bytes);
    if (!remade) return make_error(remade.error());
    stride_ = uint32_t(stride);
    return *remade;
}

}  // namespace lc::client
