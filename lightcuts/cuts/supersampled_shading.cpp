#include "lightcuts/cuts/supersampled_shading.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <ctime>
#include <memory>
#include <numbers>
#include <thread>

#include "lightcuts/cuts/cut_traversal.h"
#include "lightcuts/material_model.h"
#include "lightcuts/cuts/reconstruction_cut.h"
#include "lightcuts/seeded_mixer.h"

namespace lc {
namespace {

// The paper's image blocks: 16x16 that share nothing, started as 4x4.
constexpr uint32_t kImageBlock = 16;
constexpr uint32_t kStartBlock = 4;
// Eye rays match when their normals differ by at most 30 degrees.
const double kMatchCos = std::cos(std::numbers::pi / 6.0);
// The cone test: another point within 45 degrees of a point's normal could
// shadow it, or be shadowed by it (a concave corner).
const double kConeCos = std::cos(std::numbers::pi / 4.0);
// The samples' lightcuts refine to a quarter of the error ratio: their
// errors are shared by every eye ray between them, where per-eye-ray cuts
// err independently and average out within the pixel, and they are few
// (measured on reconstruction_cut_test's floor: at the same ratio the
// reconstruction's mean error was 2.0% against 1.7% per eye ray; at a
// quarter 0.8%, for 1.5x the rays).
constexpr double kSampleErrorScale = 0.25;
// Reconstruction cuts interpolate a node while its samples agree within half
// the error ratio: the furnished room (4,096 lights, 64x64, 4 spp) measured
// a mean error of 1.66% against 1.80% at the full ratio, for 17% more rays.
constexpr double kInterpolationScale = 0.5;
// At the pixel level, samples interpolate an eye ray no farther from any of
// them than this many times their own extent.
constexpr double kSpanFactor = 1.5;
// Materials match when their diffuse albedos differ by at most this much.
constexpr double kAlbedoMatch = 0.05;

// CPU time of the calling thread: under load the workers' share of the cores
// moves the wall clock, their own work much less.
double thread_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

bool has_lobe(const SurfacePoint& p) { return shading::has_lobe(p.specular, p.exponent); }

bool same_material(const SurfacePoint& a, const SurfacePoint& b) {
    return has_lobe(a) == has_lobe(b) && max_channel(glm::abs(a.albedo - b.albedo)) <= kAlbedoMatch &&
           max_channel(glm::abs(a.specular - b.specular)) <= kAlbedoMatch;
}

bool points_match(const EyeSample& a, const EyeSample& b) {
    return a.geometry && b.geometry && same_material(a.point, b.point) &&
           glm::dot(a.point.normal, b.point.normal) >= kMatchCos;
}

// True when q lies inside the cone around p's normal.
bool inside_cone(const SurfacePoint& p, const glm::dvec3& q) {
    const glm::dvec3 d = q - p.position;
    const double distance = glm::length(d);
    if (distance <= 1e-9) return false;
    return glm::dot(d, p.normal) >= kConeCos * distance;
}

// A rectangle of pixels [x0, x1) x [y0, y1).
struct Block {
    uint32_t x0, y0, x1, y1;
};

// The image blocks of a frame, row by row.
struct ImageBlocks {
    uint32_t width, height, across, down;

    ImageBlocks(uint32_t w, uint32_t h)
        : width(w), height(h), across((w + kImageBlock - 1) / kImageBlock),
          down((h + kImageBlock - 1) / kImageBlock) {}
    uint32_t count() const { return across * down; }
    Block operator[](uint32_t b) const {
        const uint32_t x0 = (b % across) * kImageBlock, y0 = (b / across) * kImageBlock;
        return {x0, y0, std::min(x0 + kImageBlock, width), std::min(y0 + kImageBlock, height)};
    }
};

// The corner samples of a frame, shared by the image blocks whose edges they
// lie on: a sample depends on its corner alone, so whichever block computes
// it first lends it to its neighbours (the paper's blocks share none: 25
// lightcuts for every 16 of the start grid's). Two workers computing the
// same corner at once keep the first one stored; only that one is counted.
// A sample is freed once every image block around it is done.
class CornerSamples {
public:
    explicit CornerSamples(const ImageBlocks& blocks)
        : columns_(blocks.width + 1), slots_(size_t(columns_) * (blocks.height + 1)),
          users_(slots_.size()) {
        for (uint32_t b = 0; b < blocks.count(); ++b) {
            for_each_corner(blocks[b],
                            [&](size_t at) { users_[at].fetch_add(1, std::memory_order_relaxed); });
        }
    }
    ~CornerSamples() {
        for (std::atomic<ReconstructionSample*>& slot : slots_) delete slot.load();
    }
    CornerSamples(const CornerSamples&) = delete;
    CornerSamples& operator=(const CornerSamples&) = delete;

    // The sample at corner (i, j), made by `make` into a ray count of its
    // own; `stats` and `rays` count it only when it is the one kept.
    template <typename Make>
    const ReconstructionSample& at(uint32_t i, uint32_t j, SupersampleStats& stats,
                                   ShadowRayCount& rays, Make&& make) {
        std::atomic<ReconstructionSample*>& slot = slots_[size_t(j) * columns_ + i];
        if (ReconstructionSample* kept = slot.load(std::memory_order_acquire)) return *kept;
        ShadowRayCount own;
        auto made = std::make_unique<ReconstructionSample>(make(own));
        ReconstructionSample* expected = nullptr;
        if (!slot.compare_exchange_strong(expected, made.get(), std::memory_order_acq_rel))
            return *expected;
        ++stats.lightcuts;
        rays.rays += own.rays;
        return *made.release();
    }

    // An image block is done: its corners' samples go once no block needs them.
    void release(const Block& image_block) {
        for_each_corner(image_block, [&](size_t at) {
            if (users_[at].fetch_sub(1, std::memory_order_acq_rel) == 1)
                delete slots_[at].exchange(nullptr, std::memory_order_acq_rel);
        });
    }

private:
    template <typename Visit>
    void for_each_corner(const Block& b, Visit&& visit) const {
        for (uint32_t j = b.y0; j <= b.y1; ++j)
            for (uint32_t i = b.x0; i <= b.x1; ++i) visit(size_t(j) * columns_ + i);
    }

    uint32_t columns_;
    // Owned: set once by at(), deleted by release() or the destructor.
    std::vector<std::atomic<ReconstructionSample*>> slots_;
    std::vector<std::atomic<uint32_t>> users_;
};

class BlockShader {
public:
    BlockShader(const WalkTree& tree, std::span<const SceneLight> classic, const SupersampledFrame& frame,
                const CutSettings& settings, std::vector<glm::dvec3>& sums, CornerSamples* samples)
        : tree_(tree),
          classic_(classic),
          frame_(frame),
          settings_(settings),
          sums_(sums),
          samples_(samples) {}

    // One 16x16 image block, started as 4x4 blocks.
    void shade_image_block(const Block& image_block) {
        for (uint32_t y = image_block.y0; y < image_block.y1; y += kStartBlock) {
            for (uint32_t x = image_block.x0; x < image_block.x1; x += kStartBlock) {
                shade_block({x, y, std::min(x + kStartBlock, image_block.x1),
                             std::min(y + kStartBlock, image_block.y1)});
            }
        }
    }

    void shade_per_sample(const Block& image_block) {
        for (uint32_t y = image_block.y0; y < image_block.y1; ++y) {
            for (uint32_t x = image_block.x0; x < image_block.x1; ++x) {
                for (uint32_t s = 0; s < frame_.spp(); ++s) {
                    const EyeSample& eye = frame_.eye_at(s, x, y);
                    if (!eye.geometry) {
                        add_background(x, y, eye);
                        continue;
                    }
                    ++stats.lightcuts;
                    add(x, y, eye,
                        counted_lightcut(tree_, eye.point, settings_, rays_).radiance);
                }
            }
        }
    }

    SupersampleStats stats;

    void finish() { stats.shadow_rays = rays_.rays; }

private:
    CutSettings sample_settings() const {
        CutSettings s = settings_;
        s.error_ratio *= kSampleErrorScale;
        return s;
    }

    const EyeSample& corner(uint32_t i, uint32_t j) const {
        return frame_.corners[size_t(j) * (frame_.width + 1) + i];
    }

    // The sample at corner (i, j), computed on first use.
    const ReconstructionSample& sample_at(uint32_t i, uint32_t j) {
        return samples_->at(i, j, stats, rays_, [&](ShadowRayCount& rays) {
            return make_reconstruction_sample(tree_, corner(i, j).point, sample_settings(), rays);
        });
    }

    // A background ray lights nothing: it shows what lies behind the scene.
    void add_background(uint32_t x, uint32_t y, const EyeSample& eye) {
        sums_[size_t(y) * frame_.width + x] += eye.emitted;
    }

    void add(uint32_t x, uint32_t y, const EyeSample& eye, const glm::dvec3& tree_radiance) {
        glm::dvec3 radiance = tree_radiance + eye.emitted;
        for (const SceneLight& light : classic_) radiance += shade_light(light, eye.point);
        sums_[size_t(y) * frame_.width + x] += radiance;
    }

    // The block's eye rays and corners agree: one material, close normals,
    // and no point inside another's cone.
    bool block_matches(const Block& b) const {
        std::vector<const EyeSample*> points;
        for (uint32_t j : {b.y0, b.y1})
            for (uint32_t i : {b.x0, b.x1}) points.push_back(&corner(i, j));
        for (uint32_t y = b.y0; y < b.y1; ++y)
            for (uint32_t x = b.x0; x < b.x1; ++x)
                for (uint32_t s = 0; s < frame_.spp(); ++s) points.push_back(&frame_.eye_at(s, x, y));
        for (const EyeSample* p : points) {
            if (!points_match(*p, *points.front())) return false;
        }
        for (const EyeSample* p : points) {
            for (const EyeSample* q : points) {
                if (p != q && inside_cone(p->point, q->point.position)) return false;
            }
        }
        return true;
    }

    void shade_block(const Block& b) {
        const bool pixel = b.x1 - b.x0 == 1 && b.y1 - b.y0 == 1;
        if (pixel) {
            ++stats.pixel_blocks;
            shade_pixel(b.x0, b.y0);
            return;
        }
        if (!block_matches(b)) {
            const uint32_t xm = b.x1 - b.x0 > 1 ? (b.x0 + b.x1) / 2 : b.x1;
            const uint32_t ym = b.y1 - b.y0 > 1 ? (b.y0 + b.y1) / 2 : b.y1;
            for (const Block& sub : {Block{b.x0, b.y0, xm, ym}, Block{xm, b.y0, b.x1, ym},
                                     Block{b.x0, ym, xm, b.y1}, Block{xm, ym, b.x1, b.y1}}) {
                if (sub.x0 < sub.x1 && sub.y0 < sub.y1) shade_block(sub);
            }
            return;
        }
        // Image-space bilinear weights over the block's four corners.
        const ReconstructionSample* corners[4] = {&sample_at(b.x0, b.y0), &sample_at(b.x1, b.y0),
                                                  &sample_at(b.x0, b.y1), &sample_at(b.x1, b.y1)};
        for (uint32_t y = b.y0; y < b.y1; ++y) {
            for (uint32_t x = b.x0; x < b.x1; ++x) {
                for (uint32_t s = 0; s < frame_.spp(); ++s) {
                    const glm::dvec2 at = glm::dvec2(x, y) + 0.5 + frame_.offsets[s];
                    const double u = std::clamp((at.x - b.x0) / double(b.x1 - b.x0), 0.0, 1.0);
                    const double v = std::clamp((at.y - b.y0) / double(b.y1 - b.y0), 0.0, 1.0);
                    const double weights[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
                    reconstruct(x, y, frame_.eye_at(s, x, y), corners, weights, 4);
                }
            }
        }
    }

    // A pixel-sized block: each eye ray takes the corners that match it,
    // weighted by inverse squared distance, or else a lightcut of its own.
    void shade_pixel(uint32_t x, uint32_t y) {
        const uint32_t is[4] = {x, x + 1, x, x + 1};
        const uint32_t js[4] = {y, y, y + 1, y + 1};
        for (uint32_t s = 0; s < frame_.spp(); ++s) {
            const EyeSample& eye = frame_.eye_at(s, x, y);
            if (!eye.geometry) {
                add_background(x, y, eye);
                continue;
            }
            const ReconstructionSample* matching[4];
            double weights[4];
            int count = 0;
            double total = 0.0;
            for (int c = 0; c < 4; ++c) {
                const EyeSample& at_corner = corner(is[c], js[c]);
                if (!points_match(eye, at_corner)) continue;
                const ReconstructionSample& sample = sample_at(is[c], js[c]);
                const glm::dvec3 d = sample.point.position - eye.point.position;
                matching[count] = &sample;
                weights[count] = 1.0 / std::max(glm::dot(d, d), 1e-12);
                total += weights[count++];
            }
            // The paper omits the cone test here; but where another surface
            // of the pixel rises over this point (the back wall beside the
            // cabinet) the matching corners all lie on the open side, agree,
            // and lend it light it does not get (measured: a pixel 49% off).
            if (count < 2 || pixel_rises_over(x, y, eye) || !samples_span(eye, matching, count)) {
                ++stats.lightcuts;
                add(x, y, eye, counted_lightcut(tree_, eye.point, settings_, rays_).radiance);
                continue;
            }
            for (int c = 0; c < count; ++c) weights[c] /= total;
            reconstruct(x, y, eye, matching, weights, count);
        }
    }

    // Whether the samples lie around `eye` rather than all to one side of it:
    // no sample farther from it than kSpanFactor x the samples' own extent.
    // Where the corners that match lie on one edge of a pixel that spans a
    // long stretch of surface (a ceiling at a grazing angle), the eye ray
    // would extrapolate (measured: a pixel 26% off).
    static bool samples_span(const EyeSample& eye, const ReconstructionSample* const* samples,
                             int count) {
        double extent = 0.0, reach = 0.0;
        for (int a = 0; a < count; ++a) {
            reach = std::max(reach, glm::length(samples[a]->point.position - eye.point.position));
            for (int b = a + 1; b < count; ++b)
                extent = std::max(extent, glm::length(samples[a]->point.position -
                                                      samples[b]->point.position));
        }
        return reach <= kSpanFactor * extent;
    }

    // Whether a corner or another eye ray of pixel (x, y) lies inside the
    // cone around `eye`'s normal.
    bool pixel_rises_over(uint32_t x, uint32_t y, const EyeSample& eye) const {
        for (uint32_t j = y; j <= y + 1; ++j) {
            for (uint32_t i = x; i <= x + 1; ++i) {
                const EyeSample& c = corner(i, j);
                if (c.geometry && inside_cone(eye.point, c.point.position)) return true;
            }
        }
        for (uint32_t s = 0; s < frame_.spp(); ++s) {
            const EyeSample& other = frame_.eye_at(s, x, y);
            if (other.geometry && inside_cone(eye.point, other.point.position)) return true;
        }
        return false;
    }

    void reconstruct(uint32_t x, uint32_t y, const EyeSample& eye,
                     const ReconstructionSample* const* samples, const double* weights, int count) {
        if (!eye.geometry) return;
        ++stats.reconstruction_cuts;
        add(x, y, eye,
            reconstruction_cut(tree_, eye.point, std::span(samples, size_t(count)),
                               std::span(weights, size_t(count)), settings_.error_ratio * kInterpolationScale, rays_));
    }

    const WalkTree& tree_;
    std::span<const SceneLight> classic_;
    const SupersampledFrame& frame_;
    const CutSettings& settings_;
    std::vector<glm::dvec3>& sums_;
    ShadowRayCount rays_;
    CornerSamples* samples_;  // reconstruction cuts only
};

}  // namespace

std::vector<glm::dvec3> shade_supersampled(const WalkTree& tree, std::span<const SceneLight> classic_lights,
                                           const SupersampledFrame& frame, const CutSettings& settings,
                                           SupersampleShading shading, uint32_t threads,
                                           SupersampleStats& stats) {
    std::vector<glm::dvec3> sums(size_t(frame.width) * frame.height, glm::dvec3(0.0));
    if (frame.spp() == 0) return sums;
    const ImageBlocks blocks(frame.width, frame.height);
    const uint32_t block_count = blocks.count();
    const bool reconstruction = shading == SupersampleShading::kReconstructionCuts;
    std::unique_ptr<CornerSamples> samples =
        reconstruction ? std::make_unique<CornerSamples>(blocks) : nullptr;
    std::atomic<uint32_t> next{0};
    const uint32_t workers = std::clamp(threads, 1u, std::max(block_count, 1u));
    std::vector<std::unique_ptr<BlockShader>> shaders;
    for (uint32_t w = 0; w < workers; ++w)
        shaders.push_back(
            std::make_unique<BlockShader>(tree, classic_lights, frame, settings, sums, samples.get()));
    auto work = [&](BlockShader& shader) {
        const double cpu_start = thread_cpu_ms();
        for (uint32_t b = next++; b < block_count; b = next++) {
            if (reconstruction) {
                shader.shade_image_block(blocks[b]);
                samples->release(blocks[b]);
            } else {
                shader.shade_per_sample(blocks[b]);
            }
        }
        shader.finish();
        shader.stats.cpu_ms = thread_cpu_ms() - cpu_start;
    };
    std::vector<std::thread> pool;
    for (uint32_t w = 1; w < workers; ++w) pool.emplace_back(work, std::ref(*shaders[w]));
    work(*shaders[0]);
    for (std::thread& t : pool) t.join();
    for (const auto& shader : shaders) {
        stats.shadow_rays += shader->stats.shadow_rays;
        stats.lightcuts += shader->stats.lightcuts;
        stats.reconstruction_cuts += shader->stats.reconstruction_cuts;
        stats.pixel_blocks += shader->stats.pixel_blocks;
        stats.cpu_ms += shader->stats.cpu_ms;
    }
    for (glm::dvec3& sum : sums) sum /= double(frame.spp());
    return sums;
}

std::vector<glm::dvec2> jittered_offsets(uint32_t count, uint64_t seed) {
    uint32_t n = 1;
    while (n * n < count) ++n;
    std::vector<uint32_t> cells(size_t(n) * n);
    for (uint32_t c = 0; c < cells.size(); ++c) cells[c] = c;
    SplitMix64 rng(seed);
    // Fisher-Yates with the seeded mixer, when only some cells are taken.
    if (cells.size() > count) {
        for (size_t i = cells.size() - 1; i > 0; --i)
            std::swap(cells[i], cells[size_t(rng.next() % (i + 1))]);
    }
    std::vector<glm::dvec2> offsets;
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t cell = cells[k];
        const double u = rng.uniform(), v = rng.uniform();
        offsets.emplace_back((double(cell % n) + u) / n - 0.5, (double(cell / n) + v) / n - 0.5);
    }
    return offsets;
}

}  // namespace lc
