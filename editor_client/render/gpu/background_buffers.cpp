#include "editor_client/render/gpu/background_buffers.h"

#include <span>
#include <vector>

#include "editor_client/render/gpu/storage_upload.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

namespace {

// The map's texels (one black texel for a sky or no environment, so that the
// binding always holds a buffer).
std::vector<GpuEnvironmentTexel> environment_texels(const Environment* environment) {
    if (environment == nullptr || !environment->has_map()) return {GpuEnvironmentTexel{}};
    std::vector<GpuEnvironmentTexel> texels(environment->map.texels.size());
    for (size_t i = 0; i < texels.size(); ++i) texels[i].radiance = environment->map.texels[i];
    return texels;
}

}  // namespace

Status BackgroundBuffers::create(const vk::Context& context) {
    Result<vk::Buffer> frame =
        vk::Buffer::create(context.device(), sizeof(GpuBackground),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           vk::MemoryUsage::kDeviceLocal);
    if (!frame) return make_error(frame.error());
    frame_ = std::move(frame).value();
    const std::vector<GpuEnvironmentTexel> no_texels = environment_texels(nullptr);
    return upload_storage(context, texels_, std::as_bytes(std::span(no_texels)));
}

Status BackgroundBuffers::set_environment(const vk::Context& context,
                                          std::shared_ptr<const Environment> environment) {
    const std::vector<GpuEnvironmentTexel> texels = environment_texels(environment.get());
    LC_RETURN_IF_ERROR(upload_storage(context, texels_, std::as_bytes(std::span(texels))));
    environment_ = std::move(environment);
    return Ok{};
}

}  // namespace lc::client
