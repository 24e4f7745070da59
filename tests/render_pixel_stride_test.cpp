// Strided frames (pixel_stride.h): pixel (i, j) of a frame rendered with
// stride K shades the eye ray of pixel (K i, K j) of the full frame, so a
// strided reference measures the full one's pixels in a K^2-th of the work.
// The G-buffer is rasterised at other sample positions (the same points up to
// float rounding), so the shading agrees within float tolerance. A frame
// strided over tiles renders the middle 8x8 tile of every KxK block of tiles
// over the full frame's G-buffer: exactly the full frame's pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "editor_client/render/pixel_stride.h"
#include "editor_client/render/renderer.h"
#include "render_test_support.h"

namespace lc::client {
namespace {

TEST(PixelStride, DividesTheSidesAndMovesTheEyeRays) {
    RenderSettings settings;
    settings.width = 256;
    settings.height = 128;
    Result<RenderSettings> same = strided_settings(settings, 1);
    ASSERT_TRUE(same.ok());
    EXPECT_EQ(same->width, 256u);
    EXPECT_EQ(same->pixel_offset.x, 0.0f);
    Result<RenderSettings> strided = strided_settings(settings, 4);
    ASSERT_TRUE(strided.ok()) << strided.error();
    EXPECT_EQ(strided->width, 64u);
    EXPECT_EQ(strided->height, 32u);
    EXPECT_FLOAT_EQ(strided->pixel_offset.x, -0.375f);
    EXPECT_FLOAT_EQ(strided->pixel_offset.y, -0.375f);
    EXPECT_TRUE(validate(*strided).ok());
    EXPECT_FALSE(strided_settings(settings, 3).ok()) << "3 does not divide 256";
    EXPECT_FALSE(strided_settings(settings, 0).ok());
    settings.pixel_offset = {0.25f, 0.0f};
    EXPECT_FALSE(strided_settings(settings, 2).ok()) << "an offset of its own";
}

TEST(TileStride, TakesTheMiddleTileOfEveryBlockAndGathersThem) {
    Result<std::vector<PixelRegion>> tiles = strided_tiles(64, 32, 8, 4);
    ASSERT_TRUE(tiles.ok()) << tiles.error();
    ASSERT_EQ(tiles->size(), 2u);
    EXPECT_EQ((*tiles)[0], (PixelRegion{16, 16, 8, 8}));
    EXPECT_EQ((*tiles)[1], (PixelRegion{48, 16, 8, 8}));
    EXPECT_EQ(strided_tiles(64, 32, 8, 1)->size(), 32u) << "stride 1: every tile";
    EXPECT_FALSE(strided_tiles(64, 40, 8, 4).ok()) << "32 does not divide 40";
    EXPECT_FALSE(strided_tiles(64, 32, 8, 0).ok());
    // Each pixel's value is its index in the full 64x32 image.
    std::vector<uint32_t> image(64 * 32);
    for (uint32_t i = 0; i < image.size(); ++i) image[i] = i;
    const std::vector<uint32_t> gathered = gather_tiles(std::span<const uint32_t>(image), 64, 1, *tiles, 4);
    ASSERT_EQ(gathered.size(), 16u * 8u);
    EXPECT_EQ(gathered[0], 16u * 64 + 16) << "the first tile's first pixel";
    EXPECT_EQ(gathered[7], 16u * 64 + 23);
    EXPECT_EQ(gathered[8], 16u * 64 + 48) << "the second tile beside it";
    EXPECT_EQ(gathered[16 * 7 + 15], 23u * 64 + 55) << "the second tile's last pixel";
}

// The furnished room's full reference frame (64x64, shadows on), which the
// strided frames are compared with.
class StridedReference : public test::VulkanTest {
protected:
    void render_full() {
        scene_ = make_furnished_room_scene();
        scene_.lights = test::room_lights(300, 29, LightTypeChoice::kPoint, 2.0f);
        tree_ = test::agglomerative_tree(scene_.lights);
        Result<std::unique_ptr<Renderer>> renderer = test::create_renderer(*context_, scene_, &tree_);
        ASSERT_TRUE(renderer.ok()) << renderer.error();
        renderer_ = std::move(renderer).value();
        ASSERT_TRUE(renderer_->effects().shadows);
        full_.mode = RenderMode::kReference;
        full_.width = full_.height = 64;
        full_.camera = test::furnished_room_camera();
        Result<RenderStats> stats = renderer_->render(full_);
        ASSERT_TRUE(stats.ok()) << stats.error();
        full_stats_ = *stats;
        full_hdr_ = renderer_->read_hdr().value();
    }

    Scene scene_;
    LightTree tree_;
    std::unique_ptr<Renderer> renderer_;
    RenderSettings full_;
    RenderStats full_stats_;
    std::vector<float> full_hdr_;
};

TEST_F(StridedReference, TilesAreTheFullFramesPixelsExactly) {
    ASSERT_NO_FATAL_FAILURE(render_full());
    Renderer* renderer = renderer_.get();
    const RenderSettings& full = full_;
    const std::vector<float>& full_hdr = full_hdr_;
    for (uint32_t stride : {2u, 4u}) {
        SCOPED_TRACE(testing::Message() << "tile stride " << stride);
        const std::vector<PixelRegion> tiles = strided_tiles(64, 64, 8, stride).value();
        Result<RenderStats> stats = renderer->render(full, tiles);
        ASSERT_TRUE(stats.ok()) << stats.error();
        const std::vector<float> hdr = renderer->read_hdr().value();
        const std::vector<float> gathered =
            gather_tiles(std::span<const float>(hdr), 64, 4, tiles, stride);
        const std::vector<float> expected =
            gather_tiles(std::span<const float>(full_hdr), 64, 4, tiles, stride);
        ASSERT_EQ(gathered.size(), size_t(64 / stride) * (64 / stride) * 4);
        size_t lit = 0, differ = 0;
        for (size_t i = 0; i < gathered.size(); i += 4) {
            lit += expected[i + 3] != 0.0f;
            for (int c = 0; c < 4; ++c) differ += gathered[i + c] != expected[i + c];
        }
        EXPECT_EQ(differ, 0u) << "the same G-buffer and the same sums";
        EXPECT_GT(lit, gathered.size() / 4 / 2);
        EXPECT_EQ(stats->geometry_pixels, lit) << "the counters see the tiles only";
        EXPECT_EQ(stats->cuts.avg_cut, double(renderer->leaf_count())) << "over the tiles' pixels";
        EXPECT_GT(stats->shadows.rays, 0u);
        EXPECT_LT(stats->shadows.rays, full_stats_.shadows.rays);
    }
}

TEST_F(StridedReference, ShadesTheFullFramesPixels) {
    ASSERT_NO_FATAL_FAILURE(render_full());
    Renderer* renderer = renderer_.get();
    const RenderSettings& full = full_;
    const std::vector<float>& full_hdr = full_hdr_;
    for (uint32_t stride : {2u, 4u}) {
        SCOPED_TRACE(testing::Message() << "stride " << stride);
        RenderSettings strided = strided_settings(full, stride).value();
        Result<RenderStats> stats = renderer->render(strided);
        ASSERT_TRUE(stats.ok()) << stats.error();
        const std::vector<float> hdr = renderer->read_hdr().value();
        size_t geometry = 0, agree = 0, background_mismatch = 0, strided_lit = 0;
        for (uint32_t j = 0; j < strided.height; ++j)
            for (uint32_t i = 0; i < strided.width; ++i) {
                const size_t at = 4 * (size_t(j) * strided.width + i);
                const size_t full_at = 4 * (size_t(stride * j) * full.width + stride * i);
                const bool lit = hdr[at + 3] != 0.0f, full_lit = full_hdr[full_at + 3] != 0.0f;
                background_mismatch += lit != full_lit;
                strided_lit += lit;
                if (!full_lit) continue;
                ++geometry;
                bool close = true;
                for (int c = 0; c < 3; ++c) {
                    const double want = full_hdr[full_at + c];
                    close = close && std::abs(double(hdr[at + c]) - want) <= 1e-3 * want + 1e-7;
                }
                agree += close;
            }
        std::printf("  stride %u: %zu of %zu geometry pixels agree, %zu coverage mismatches\n",
                    stride, agree, geometry, background_mismatch);
        EXPECT_GT(geometry, size_t(strided.width) * strided.height / 2);
        // A shadow edge or silhouette through a pixel centre may fall either
        // way under another rounding; the rest is the same work.
        EXPECT_GE(agree, geometry * 97 / 100);
        EXPECT_LE(background_mismatch, 1u);
        EXPECT_EQ(stats->geometry_pixels, strided_lit);
        EXPECT_GT(stats->shadows.rays, 0u);
    }
}

}  // namespace
}  // namespace lc::client
