#include "editor_client/vk/context.h"

#include <spdlog/spdlog.h>

namespace lc::vk {

Result<Context> Context::create(const ContextOptions& options) {
    Context context;
    InstanceOptions instance_options;
    instance_options.validation = options.validation;
    instance_options.extensions = options.instance_extensions;
    Result<Instance> instance = Instance::create(instance_options);
    if (!instance) return make_error("Vulkan instance: " + instance.error());
    context.instance_ = std::move(instance).value();

    if (options.create_surface) {
        Result<VkSurfaceKHR> surface = options.create_surface(context.instance_.handle());
        if (!surface) return make_error("window surface: " + surface.error());
        context.surface_ = Surface(context.instance_.handle(), *surface);
    }

    Result<PhysicalDevice> physical =
        select_physical_device(context.instance_.handle(), context.surface_.handle());
    if (!physical) return make_error(physical.error());
    spdlog::info("vulkan device: {}{}", physical->name(),
                 context.instance_.validation_enabled() ? " (validation on)" : "");

    Result<Device> device = Device::create(*physical, context.surface_.handle() != VK_NULL_HANDLE);
    if (!device) return make_error("Vulkan device: " + device.error());
    context.device_ = std::move(device).value();

    Result<CommandPool> pool = CommandPool::create(context.device_);
    if (!pool) return make_error(pool.error());
    context.pool_ = std::move(pool).value();
    return context;
}

}  // namespace lc::vk
