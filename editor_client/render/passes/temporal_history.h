#pragma once
// The real-time mode's history: what it has accumulated, the world positions
// it was shaded at, two of each (the previous frame's, read, and this frame's,
// written, swapped every frame), the descriptor sets that bind them (set
// kTemporalSet) and the parameters the temporal pass reads. Decides whether a
// frame continues the history (same settings; the camera may move) or starts
// it again.
#include <vulkan/vulkan.h>

#include <glm/mat4x4.hpp>

#include <array>
#include <cstdint>
#include <optional>

#include "editor_client/render/settings/render_settings.h"
#include "editor_client/vk/buffer.h"
#include "editor_client/vk/descriptor_set.h"
#include "editor_client/vk/device.h"
#include "editor_client/vk/image.h"
#include "lightcuts/tree/gpu_layout.h"
#include "lightcuts/result.h"

namespace lc::client {

// Frames after which a resting real-time view counts as refined (the spatial
// filter is gone: the image is the accumulated mean itself).
inline constexpr uint32_t kRealtimeRefinedFrames = 16;

// How much history the temporal pass keeps (GpuTemporalParams).
struct TemporalPolicy {
    uint32_t still_history_cap = 1u << 20;  // a resting view: the mean of every frame
    uint32_t moving_history_cap = 12;       // a moving one: MegaLights keeps at most 12
    uint32_t filter_frames = kRealtimeRefinedFrames;  // the spatial filter fades out over these
    float position_tolerance = 0.02f;       // reprojection, x the eye distance
    // The frames' draws step along Weyl sequences (frame_strata.glsl); false
    // draws every frame independently (what render_realtime_test compares).
    bool spread_frames = true;
};

class TemporalHistory {
public:
    static Result<TemporalHistory> create(const vk::Device& device);

    VkDescriptorSetLayout set_layout() const { return set_layout_.handle(); }

    // Sizes the images for a frame (remade, and the history dropped, when the
    // size differs) and works out what the frame with these settings reads.
    // Called once or more before recording; changes nothing the GPU reads.
    Status prepare(const RenderSettings& settings);
    // The set binding this frame's history (prepare first).
    VkDescriptorSet descriptor_set() const { return sets_[parity_]; }
    // Records the images' transitions and the parameters' upload.
    void record_setup(VkCommandBuffer cmd) const;
    // After a frame was recorded: its output is the next frame's history.
    void advance();
    // The next frame starts a new history (a new tree, new lights).
    void drop() { last_.reset(); }

    const GpuTemporalParams& params() const { return params_; }
    // Frames of the still view the last recorded frame ends (1 after a new
    // start or a camera move; a moving view keeps a short history besides).
    uint32_t frames_accumulated() const { return frame_number_; }
    void set_policy(const TemporalPolicy& policy) { policy_ = policy; }
    const TemporalPolicy& policy() const { return policy_; }

private:
    struct Images {
        std::array<vk::Image, 2> history;
        std::array<vk::Image, 2> positions;
    };

    TemporalHistory(const vk::Device& device) : device_(&device) {}
    Status make_images(uint32_t width, uint32_t height);
    void bind_sets();

    const vk::Device* device_;
    vk::DescriptorSetLayout set_layout_;
    vk::DescriptorPool pool_;
    std::array<VkDescriptorSet, 2> sets_{};
    vk::Buffer params_buffer_;
    Images images_;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
    bool images_fresh_ = true;  // not yet in VK_IMAGE_LAYOUT_GENERAL
    uint32_t parity_ = 0;
    TemporalPolicy policy_;
    // The last recorded frame's settings and view (none: no history).
    struct Recorded {
        RenderSettings settings;
        glm::mat4 view_proj;
    };
    std::optional<Recorded> last_;
    std::optional<Recorded> pending_;
    GpuTemporalParams params_;
    uint32_t frame_number_ = 0;
};

// The settings that decide what a real-time frame's light is: a change of any
// other than the camera, the jitter or the exposure starts a new history.
bool same_history_settings(const RenderSettings& a, const RenderSettings& b);
// World to clip space of a frame's eye rays (perspective x and y do not
// depend on the depth range, so the scene's bounds are not needed).
glm::mat4 reprojection_view_proj(const RenderSettings& settings);

}  // namespace lc::client
