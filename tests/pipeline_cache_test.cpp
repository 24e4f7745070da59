// PipelineCache: one pipeline per (layout, module, specialization values),
// found again on the same key, the least recently used dropped at capacity.
#include <gtest/gtest.h>

#include <memory>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"
#include "editor_client/render/gpu/frame_set_layout.h"
#include "editor_client/render/gpu/pipeline_cache.h"
#include "editor_client/vk/context.h"
#include "editor_client/vk/pipeline_layout.h"
#include "lightcuts/tree/gpu_layout.h"
#include "render_test_support.h"
#include "tone_map_comp.spv.h"

namespace lc::client {
namespace {

class PipelineCacheTest : public ::testing::Test {
protected:
    void SetUp() override {
        LC_REQUIRE_VULKAN(context_);
        VkDevice device = context_->device().handle();
        Result<vk::DescriptorSetLayout> set_layout = create_frame_set_layout(device);
        ASSERT_TRUE(set_layout) << set_layout.error();
        set_layout_ = std::move(set_layout).value();
        VkDescriptorSetLayout handle = set_layout_.handle();
        VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GpuFrameConstants)};
        Result<vk::PipelineLayout> layout =
            vk::PipelineLayout::create(device, std::span(&handle, 1), std::span(&range, 1));
        ASSERT_TRUE(layout) << layout.error();
        layout_ = std::move(layout).value();
    }

    // The tone-map pipeline for a workgroup of `size` x `size`.
    Result<VkPipeline> tone_map(PipelineCache& cache, uint32_t size) {
        vk::Specialization spec;
        spec.set_uint(kSpecWorkgroupX, size).set_uint(kSpecWorkgroupY, size);
        return cache.compute(layout_.handle(), std::span<const uint32_t>(tone_map_comp_spv),
                             spec);
    }

    bool cached(const PipelineCache& cache, uint32_t size) const {
        vk::Specialization spec;
        spec.set_uint(kSpecWorkgroupX, size).set_uint(kSpecWorkgroupY, size);
        return cache.contains(layout_.handle(), std::span<const uint32_t>(tone_map_comp_spv), spec);
    }

    std::unique_ptr<vk::Context> context_;
    vk::DescriptorSetLayout set_layout_;
    vk::PipelineLayout layout_;
};

TEST_F(PipelineCacheTest, SameKeyFindsTheSamePipeline) {
    PipelineCache cache(context_->device().handle());
    Result<VkPipeline> a = tone_map(cache, 8);
    ASSERT_TRUE(a) << a.error();
    Result<VkPipeline> b = tone_map(cache, 4);
    ASSERT_TRUE(b) << b.error();
    EXPECT_NE(*a, *b) << "other specialization values, another pipeline";
    Result<VkPipeline> again = tone_map(cache, 8);
    ASSERT_TRUE(again);
    EXPECT_EQ(*again, *a);
    EXPECT_EQ(cache.size(), 2u);
}

TEST_F(PipelineCacheTest, LeastRecentlyUsedGoesAtCapacity) {
    PipelineCache cache(context_->device().handle(), 2);
    ASSERT_TRUE(tone_map(cache, 8));
    ASSERT_TRUE(tone_map(cache, 4));
    ASSERT_TRUE(tone_map(cache, 8));  // 4 is now the least recently used
    ASSERT_TRUE(tone_map(cache, 2));
    EXPECT_EQ(cache.size(), 2u);
    EXPECT_TRUE(cached(cache, 8));
    EXPECT_FALSE(cached(cache, 4));
    EXPECT_TRUE(cached(cache, 2));
}

}  // namespace
}  // namespace lc::client
