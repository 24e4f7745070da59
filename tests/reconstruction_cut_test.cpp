// Reconstruction cuts (lightcuts/cuts/reconstruction_cut.h) and the supersampled
// image they shade (lightcuts/cuts/supersampled_shading.h), on the CPU: a floor
// under a square table top lit by lights above it, seen from straight above
// with 16 jittered eye rays per pixel; the reference sums every light with
// its shadow ray at every eye ray.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "lightcuts/cuts/reconstruction_cut.h"
#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/cuts/supersampled_shading.h"
#include "tree_fixtures.h"

namespace lc {
namespace {

using test::max_channel;

constexpr uint32_t kSide = 32;       // pixels
constexpr double kFloorHalf = 2.0;   // the image spans [-2, 2]^2 of the floor
constexpr uint32_t kSpp = 16;

struct FloorScene {
    std::vector<SceneLight> lights;
    WalkTree tree;
    ShadowBvh occluders;
};

FloorScene floor_scene() {
    FloorScene s;
    std::mt19937_64 rng(7);
    s.lights = test::random_lights_in_box(rng, 512, LightType::kPoint, {-3.0f, -3.0f, 1.5f},
                                          {3.0f, 3.0f, 2.5f}, false);
    s.tree = test::walk_tree(test::morton_pairing_tree(s.lights, 11));
    // A table top 0.8 above the floor: two triangles over [-0.6, 0.6]^2.
    const std::vector<glm::vec3> top = {{-0.6f, -0.6f, 0.8f}, {0.6f, -0.6f, 0.8f},
                                        {0.6f, 0.6f, 0.8f},   {-0.6f, -0.6f, 0.8f},
                                        {0.6f, 0.6f, 0.8f},   {-0.6f, 0.6f, 0.8f}};
    s.occluders = ShadowBvh::build(top);
    return s;
}

// The floor at image position (u, v) (pixels; the image spans the floor's
// [-2, 2]^2); the right half is darker, so blocks there split at the seam.
EyeSample floor_at(const FloorScene& scene, double u, double v) {
    EyeSample e;
    e.geometry = true;
    const double x = -kFloorHalf + 2.0 * kFloorHalf * u / kSide;
    const double y = -kFloorHalf + 2.0 * kFloorHalf * v / kSide;
    e.point = test::surface({x, y, 0.0}, {0, 0, 1}, x < 0.3 ? glm::dvec3(0.8) : glm::dvec3(0.4));
    e.point.occluders = &scene.occluders;
    e.point.shadow_bias = 1e-4;
    return e;
}

SupersampledFrame floor_frame(const FloorScene& scene) {
    SupersampledFrame f;
    f.width = f.height = kSide;
    f.offsets = jittered_offsets(kSpp, 3);
    for (uint32_t s = 0; s < kSpp; ++s)
        for (uint32_t y = 0; y < kSide; ++y)
            for (uint32_t x = 0; x < kSide; ++x)
                f.eye.push_back(
                    floor_at(scene, x + 0.5 + f.offsets[s].x, y + 0.5 + f.offsets[s].y));
    for (uint32_t j = 0; j <= kSide; ++j)
        for (uint32_t i = 0; i <= kSide; ++i) f.corners.push_back(floor_at(scene, i, j));
    return f;
}

// Every light with its shadow ray, at every eye ray, averaged per pixel.
std::vector<glm::dvec3> reference_image(const FloorScene& scene, const SupersampledFrame& f) {
    std::vector<glm::dvec3> out(size_t(kSide) * kSide, glm::dvec3(0.0));
    for (uint32_t s = 0; s < kSpp; ++s)
        for (size_t i = 0; i < out.size(); ++i)
            out[i] += shade_reference(scene.lights, f.eye[s * out.size() + i].point) / double(kSpp);
    return out;
}

struct ImageError {
    double mean = 0.0;
    double max = 0.0;
};

ImageError relative_error(const std::vector<glm::dvec3>& image,
                          const std::vector<glm::dvec3>& reference) {
    ImageError e;
    for (size_t i = 0; i < image.size(); ++i) {
        const double rel = max_channel(glm::abs(image[i] - reference[i])) /
                           std::max(max_channel(reference[i]), 1e-12);
        e.mean += rel / double(image.size());
        e.max = std::max(e.max, rel);
    }
    return e;
}

CutSettings bound_settings(double error_ratio) {
    CutSettings s;
    s.criterion = CutCriterion::kBound;
    s.search = BoundSearch::kHeap;
    s.error_ratio = error_ratio;
    return s;
}

TEST(ReconstructionCut, OneSampleAtThePointReproducesItsLightcut) {
    const FloorScene scene = floor_scene();
    const EyeSample eye = floor_at(scene, 5.3, 20.7);
    ShadowRayCount rays;
    const ReconstructionSample sample =
        make_reconstruction_sample(scene.tree, eye.point, bound_settings(0.02), rays);
    ASSERT_GT(max_channel(sample.radiance), 0.0);
    const ReconstructionSample* samples[] = {&sample};
    const double weights[] = {1.0};
    ShadowRayCount reconstruction_rays;
    const glm::dvec3 r =
        reconstruction_cut(scene.tree, eye.point, samples, weights, 0.02, reconstruction_rays);
    // The root's impostor reproduces the whole estimate, with no shadow ray.
    test::expect_near_rel(r, sample.radiance, 1e-9);
    EXPECT_EQ(reconstruction_rays.rays, 0u);
}

TEST(ReconstructionCut, SamplesInFullShadowDiscardEveryLightWithoutRays) {
    FloorScene scene = floor_scene();
    // A ceiling under the lights hides all of them from the floor.
    const std::vector<glm::vec3> lid = {{-9, -9, 1.2f}, {9, -9, 1.2f}, {9, 9, 1.2f},
                                        {-9, -9, 1.2f}, {9, 9, 1.2f},  {-9, 9, 1.2f}};
    scene.occluders = ShadowBvh::build(lid);
    ShadowRayCount rays;
    const ReconstructionSample a =
        make_reconstruction_sample(scene.tree, floor_at(scene, 4, 4).point, bound_settings(0.02), rays);
    const ReconstructionSample b =
        make_reconstruction_sample(scene.tree, floor_at(scene, 8, 4).point, bound_settings(0.02), rays);
    EXPECT_EQ(max_channel(a.radiance), 0.0);
    const ReconstructionSample* samples[] = {&a, &b};
    const double weights[] = {0.5, 0.5};
    ShadowRayCount reconstruction_rays;
    const glm::dvec3 r = reconstruction_cut(scene.tree, floor_at(scene, 6, 4).point, samples,
                                            weights, 0.02, reconstruction_rays);
    EXPECT_EQ(max_channel(r), 0.0);
    EXPECT_EQ(reconstruction_rays.rays, 0u);
}

TEST(SupersampledShading, ReconstructionNeedsFarFewerShadowRaysAtEqualError) {
    const FloorScene scene = floor_scene();
    const SupersampledFrame frame = floor_frame(scene);
    const std::vector<glm::dvec3> reference = reference_image(scene, frame);
    SupersampleStats per_sample, reconstructed;
    const std::vector<glm::dvec3> lightcuts =
        shade_supersampled(scene.tree, {}, frame, bound_settings(0.02),
                           SupersampleShading::kPerSampleLightcuts, 2, per_sample);
    const std::vector<glm::dvec3> reconstruction =
        shade_supersampled(scene.tree, {}, frame, bound_settings(0.02),
                           SupersampleShading::kReconstructionCuts, 2, reconstructed);
    const ImageError lightcuts_error = relative_error(lightcuts, reference);
    const ImageError reconstruction_error = relative_error(reconstruction, reference);
    std::printf("per-sample lightcuts: %llu rays, mean error %.4f, max %.4f\n"
                "reconstruction cuts: %llu rays (%llu lightcuts, %llu reconstruction cuts, %llu "
                "pixel blocks), mean error %.4f, max %.4f\n",
                (unsigned long long)per_sample.shadow_rays, lightcuts_error.mean,
                lightcuts_error.max, (unsigned long long)reconstructed.shadow_rays,
                (unsigned long long)reconstructed.lightcuts,
                (unsigned long long)reconstructed.reconstruction_cuts,
                (unsigned long long)reconstructed.pixel_blocks, reconstruction_error.mean,
                reconstruction_error.max);
    EXPECT_EQ(per_sample.lightcuts, uint64_t(kSide) * kSide * kSpp);
    EXPECT_GE(reconstructed.lightcuts + reconstructed.reconstruction_cuts, uint64_t(kSide) * kSide * kSpp);
    // The target: at least 5x fewer shadow rays than per-sample lightcuts.
    EXPECT_LE(reconstructed.shadow_rays * 5, per_sample.shadow_rays);
    // The stated bound: mean relative error within 1% of the 16-spp reference
    // and no pixel off by more than 5% (the shadow's edge is where they differ).
    EXPECT_LE(reconstruction_error.mean, 0.01);
    EXPECT_LE(reconstruction_error.mean, lightcuts_error.mean);
    EXPECT_LE(reconstruction_error.max, 0.05);
    for (const glm::dvec3& r : reconstruction) EXPECT_TRUE(test::finite3(r));
}

TEST(SupersampledShading, TheImageDoesNotDependOnTheWorkers) {
    const FloorScene scene = floor_scene();
    const SupersampledFrame frame = floor_frame(scene);
    SupersampleStats one, three;
    const std::vector<glm::dvec3> a = shade_supersampled(
        scene.tree, {}, frame, bound_settings(0.02), SupersampleShading::kReconstructionCuts, 1, one);
    const std::vector<glm::dvec3> b = shade_supersampled(
        scene.tree, {}, frame, bound_settings(0.02), SupersampleShading::kReconstructionCuts, 3, three);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::dvec3)), 0);
    EXPECT_EQ(one.shadow_rays, three.shadow_rays);
    EXPECT_EQ(one.lightcuts, three.lightcuts);
}

TEST(SupersampledShading, ImageBlocksShareTheSamplesOnTheirEdges) {
    // One material, no occluders: no block splits, so the lightcuts are the
    // start grid's corners, each once (the 2x2 image blocks' own corners
    // would be 4 x 25).
    FloorScene scene = floor_scene();
    SupersampledFrame frame;
    frame.width = frame.height = kSide;
    frame.offsets = {glm::dvec2(0.0)};
    auto uniform_floor = [&](double u, double v) {
        EyeSample e = floor_at(scene, u, v);
        e.point.albedo = glm::dvec3(0.6);
        e.point.occluders = nullptr;
        return e;
    };
    for (uint32_t y = 0; y < kSide; ++y)
        for (uint32_t x = 0; x < kSide; ++x) frame.eye.push_back(uniform_floor(x + 0.5, y + 0.5));
    for (uint32_t j = 0; j <= kSide; ++j)
        for (uint32_t i = 0; i <= kSide; ++i) frame.corners.push_back(uniform_floor(i, j));
    for (uint32_t workers : {1u, 2u, 5u}) {
        SupersampleStats stats;
        shade_supersampled(scene.tree, {}, frame, bound_settings(0.02),
                           SupersampleShading::kReconstructionCuts, workers, stats);
        const uint64_t corners_across = kSide / 4 + 1;
        EXPECT_EQ(stats.lightcuts, corners_across * corners_across) << workers << " workers";
        EXPECT_EQ(stats.reconstruction_cuts, uint64_t(kSide) * kSide);
        EXPECT_GT(stats.cpu_ms, 0.0);
    }
}

TEST(JitteredOffsets, OnePerStratumSeededAndInsideThePixel) {
    const std::vector<glm::dvec2> a = jittered_offsets(16, 5);
    EXPECT_EQ(a, jittered_offsets(16, 5));
    EXPECT_NE(a, jittered_offsets(16, 6));
    std::vector<int> cells(16, 0);
    for (const glm::dvec2& o : a) {
        ASSERT_GE(o.x, -0.5);
        ASSERT_LT(o.x, 0.5);
        ASSERT_GE(o.y, -0.5);
        ASSERT_LT(o.y, 0.5);
        ++cells[size_t(std::floor((o.y + 0.5) * 4) * 4 + std::floor((o.x + 0.5) * 4))];
    }
    for (int c : cells) EXPECT_EQ(c, 1);
    // Not a square: distinct cells of the next square grid.
    const std::vector<glm::dvec2> five = jittered_offsets(5, 5);
    ASSERT_EQ(five.size(), 5u);
    std::vector<int> taken(9, 0);
    for (const glm::dvec2& o : five)
        ++taken[size_t(std::floor((o.y + 0.5) * 3) * 3 + std::floor((o.x + 0.5) * 3))];
    for (int c : taken) EXPECT_LE(c, 1);
}

}  // namespace
}  // namespace lc
