#pragma once
// What pixels without geometry show, on the GPU: the environment's texels
// (uploaded once per environment; none: black) and the buffer each frame's
// commands write its GpuBackground into (background.h).
#include <vulkan/vulkan.h>

#include <memory>

#include "editor_client/vk/buffer.h"
#include "editor_client/vk/context.h"
#include "lightcuts/environment.h"
#include "lightcuts/result.h"

namespace lc::client {

class BackgroundBuffers {
public:
    // The frame's buffer, and no environment.
    Status create(const vk::Context& context);
    Status set_environment(const vk::Context& context, std::shared_ptr<const Environment> environment);

    const Environment* environment() const { return environment_.get(); }
    VkBuffer frame() const { return frame_.handle(); }
    VkBuffer texels() const { return texels_.handle(); }

private:
    std::shared_ptr<const Environment> environment_;
    vk::Buffer frame_;   // GpuBackground, rewritten by every frame's commands
    vk::Buffer texels_;  // GpuEnvironmentTexel
};

}  // namespace lc::client
