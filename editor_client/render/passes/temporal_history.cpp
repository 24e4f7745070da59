#include "editor_client/render/passes/temporal_history.h"

#include "editor_client/render/passes/compute_pass.h"
#include "editor_client/render/passes/gbuffer_pass.h"
#include "editor_client/vk/barriers.h"
#include "lightcuts/device/bindings.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

constexpr VkFormat kHistoryFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

Result<vk::DescriptorSetLayout> create_set_layout(VkDevice device) {
    std::array<VkDescriptorType, kTemporalBindingCount> types{};
    for (uint32_t b = 0; b < kTemporalBindingCount; ++b)
        types[b] = b == kBindTemporalParams ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    return vk::DescriptorSetLayout::create(device, types, VK_SHADER_STAGE_COMPUTE_BIT);
}

}  // namespace

bool same_history_settings(const RenderSettings& a, const RenderSettings& b) {
    RenderSettings a_light = a;
    a_light.camera = b.camera;
    a_light.pixel_offset = b.pixel_offset;
    a_light.exposure = b.exposure;
    return a_light == b;
}

glm::mat4 reprojection_view_proj(const RenderSettings& settings) {
    const glm::vec3 target = settings.camera.target;
    return eye_ray_view_projection(settings, settings.width, settings.height, target, target);
}

Result<TemporalHistory> TemporalHistory::create(const vk::Device& device) {
    TemporalHistory history(device);
    Result<vk::DescriptorSetLayout> layout = create_set_layout(device.handle());
    if (!layout) return make_error(layout.error());
    history.set_layout_ = std::move(layout).value();
    std::array<VkDescriptorPoolSize, 2> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2 * (kTemporalBindingCount - 1)},
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2}};
    Result<vk::DescriptorPool> pool = vk::DescriptorPool::create(device.handle(), 2, sizes);
    if (!pool) return make_error(pool.error());
    history.pool_ = std::move(pool).value();
    for (VkDescriptorSet& set : history.sets_) {
        Result<VkDescriptorSet> allocated = history.pool_.allocate(history.set_layout_);
        if (!allocated) return make_error(allocated.error());
        set = *allocated;
    }
    Result<vk::Buffer> params =
        vk::Buffer::create(device, sizeof(GpuTemporalParams),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           vk::MemoryUsage::kDeviceLocal);
    if (!params) return make_error(params.error());
    history.params_buffer_ = std::move(params).value();
    return history;
}

Status TemporalHistory::make_images(uint32_t width, uint32_t height) {
    // The old images and sets may be in a frame still in flight.
    LC_RETURN_IF_ERROR(device_->wait_idle());
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    for (std::array<vk::Image, 2>* pair : {&images_.history, &images_.positions}) {
        for (vk::Image& image : *pair) {
            Result<vk::Image> made =
                vk::Image::create(*device_, {width, height, kHistoryFormat, usage});
            if (!made) return make_error("real-time history: " + made.error());
            image = std::move(made).value();
        }
    }
    width_ = width;
    height_ = height;
    images_fresh_ = true;
    last_.reset();
    bind_sets();
    return Ok{};
}

// Set p reads the images of index p and writes those of index 1 - p.
void TemporalHistory::bind_sets() {
    for (uint32_t p = 0; p < 2; ++p) {
        vk::DescriptorWriter(sets_[p])
            .storage_image(kBindHistoryIn, images_.history[p].view())
            .storage_image(kBindHistoryOut, images_.history[1 - p].view())
            .storage_image(kBindHistoryPositionIn, images_.positions[p].view())
            .storage_image(kBindHistoryPositionOut, images_.positions[1 - p].view())
            .storage_buffer(kBindTemporalParams, params_buffer_.handle())
            .update(device_->handle());
    }
}

Status TemporalHistory::prepare(const RenderSettings& settings) {
    if (settings.width != width_ || settings.height != height_)
        LC_RETURN_IF_ERROR(make_images(settings.width, settings.height));
    pending_ = Recorded{settings, reprojection_view_proj(settings)};
    const bool continues = last_ && same_history_settings(last_->settings, settings);
    params_ = GpuTemporalParams{};
    params_.history_valid = continues ? 1u : 0u;
    params_.camera_moved = continues && (last_->settings.camera != settings.camera ||
                                         last_->settings.pixel_offset != settings.pixel_offset)
                               ? 1u
                               : 0u;
    if (continues) params_.previous_view_proj = last_->view_proj;
    params_.still_history_cap = policy_.still_history_cap;
    params_.moving_history_cap = policy_.moving_history_cap;
    params_.filter_frames = policy_.filter_frames;
    params_.position_tolerance = policy_.position_tolerance;
    return Ok{};
}

void TemporalHistory::record_setup(VkCommandBuffer cmd) const {
    // Fresh images hold nothing yet (the history is dropped with them).
    const VkImageLayout old_layout =
        images_fresh_ ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_GENERAL;
    for (const std::array<vk::Image, 2>* pair : {&images_.history, &images_.positions}) {
        for (const vk::Image& image : *pair) {
            vk::transition_image(cmd, {image.handle(), old_layout, VK_IMAGE_LAYOUT_GENERAL,
                                       kComputeStage, kStorageReadWrite, kComputeStage,
                                       kStorageReadWrite});
        }
    }
    vkCmdUpdateBuffer(cmd, params_buffer_.handle(), 0, sizeof(params_), &params_);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       kComputeStage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

void TemporalHistory::advance() {
    if (!pending_) return;
    const bool resting = params_.history_valid && !params_.camera_moved;
    frame_number_ = resting ? frame_number_ + 1 : 1;
    last_ = pending_;
    pending_.reset();
    parity_ = 1 - parity_;
    images_fresh_ = false;
}

}  // namespace lc::client
