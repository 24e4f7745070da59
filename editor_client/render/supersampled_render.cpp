#include "editor_client/render/supersampled_render.h"

#include <chrono>
#include <cmath>

#include "editor_client/render/background.h"
#include "editor_client/render/gbuffer_surface.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

// The G-buffer of one frame as eye samples (occluders added when shadows are traced).
Result<std::vector<EyeSample>> eye_samples(Renderer& renderer, const RenderSettings& settings) {
    LC_RETURN_IF_ERROR(renderer.render_gbuffer(settings));
    Result<GBufferReadback> g = renderer.read_gbuffer();
    if (!g) return make_error(g.error());
    const bool shadows = renderer.effects().shadows && !renderer.shadow_bvh().empty();
    const Environment* environment = renderer.environment();
    const GpuBackground background = renderer.background(settings);
    std::vector<EyeSample> out(size_t(g->width) * g->height);
    for (size_t i = 0; i < out.size(); ++i) {
        out[i].geometry = g->position[4 * i + 3] != 0.0f;
        out[i].point = gbuffer_surface_point(*g, i);
        if (shadows) {
            out[i].point.occluders = &renderer.shadow_bvh();
            out[i].point.shadow_bias = renderer.shadow_bias();
        }
        out[i].emitted = {g->emissive[4 * i], g->emissive[4 * i + 1], g->emissive[4 * i + 2]};
        if (!out[i].geometry && environment != nullptr) {
            const glm::dvec3 ray =
                background_eye_ray(background, double(i % g->width) + 0.5, double(i / g->width) + 0.5);
            out[i].emitted = environment_radiance(*environment, ray);
        }
    }
    return out;
}

// Adds one frame's read-back to the running sum, RGBA.
void accumulate(std::vector<double>& sum, std::span<const float> hdr) {
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += hdr[i];
}

// The mean as floats, alpha the share of eye rays that hit geometry (0 marks
// the background, as on the GPU); non-finite pixels counted and written as 0.
std::vector<float> resolve(std::span<const glm::dvec3> radiance, const SupersampledFrame& frame,
                           uint64_t& nonfinite) {
    std::vector<float> hdr(radiance.size() * 4);
    for (size_t i = 0; i < radiance.size(); ++i) {
        uint32_t hits = 0;
        for (uint32_t s = 0; s < frame.spp(); ++s)
            hits += frame.eye[size_t(s) * radiance.size() + i].geometry ? 1u : 0u;
        glm::dvec3 r = radiance[i];
        if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z)) {
            ++nonfinite;
            r = glm::dvec3(0.0);
        }
        hdr[4 * i] = float(r.x);
        hdr[4 * i + 1] = float(r.y);
        hdr[4 * i + 2] = float(r.z);
        hdr[4 * i + 3] = float(hits) / float(frame.spp());
    }
    return hdr;
}

Result<SupersampledImage> render_gpu_frames(Renderer& renderer, const RenderSettings& settings,
                                            std::span<const glm::dvec2> offsets) {
    SupersampledImage image;
    std::vector<double> sum(size_t(settings.width) * settings.height * 4, 0.0);
    for (const glm::dvec2& offset : offsets) {
        RenderSettings frame = settings;
        frame.pixel_offset = glm::vec2(offset);
        Result<RenderStats> stats = renderer.render(frame);
        if (!stats) return make_error(stats.error());
        image.shading_ms += stats->timing.render_ms;
        image.shadow_rays += stats->shadows.rays;
        image.nonfinite_pixels += stats->nonfinite_pixels;
        Result<std::vector<float>> hdr = renderer.read_hdr();
        if (!hdr) return make_error(hdr.error());
        accumulate(sum, *hdr);
    }
    image.hdr.resize(sum.size());
    for (size_t i = 0; i < sum.size(); ++i) image.hdr[i] = float(sum[i] / double(offsets.size()));
    return image;
}

}  // namespace

const char* spp_method_name(SppMethod method) { return name_in(kSppMethodNames, method); }

std::optional<SppMethod> parse_spp_method(std::string_view text) { return value_in(kSppMethodNames, text); }

Result<SupersampledImage> render_supersampled(Renderer& renderer, const RenderSettings& settings,
                                              const SupersampleRequest& request, const WalkTree* tree,
                                              std::span<const SceneLight> classic_lights) {
    if (request.spp == 0) return make_error("--spp must be at least 1");
    // One eye ray per pixel passes through its centre, as in a plain frame.
    const std::vector<glm::dvec2> offsets = request.spp == 1
                                                ? std::vector<glm::dvec2>{glm::dvec2(0.0)}
                                                : jittered_offsets(request.spp, request.seed);
    if (request.method == SppMethod::kGpu) return render_gpu_frames(renderer, settings, offsets);
    if (tree == nullptr || tree->empty())
        return make_error(std::string("--spp-method ") + spp_method_name(request.method) +
                          " needs a light tree");
    if (settings.criterion != CutCriterion::kBound)
        return make_error("the CPU supersampling methods use the bound criterion");

    SupersampledFrame frame;
    frame.width = settings.width;
    frame.height = settings.height;
    frame.offsets = offsets;
    for (const glm::dvec2& offset : offsets) {
        RenderSettings eye = settings;
        eye.pixel_offset = glm::vec2(offset);
        Result<std::vector<EyeSample>> samples = eye_samples(renderer, eye);
        if (!samples) return make_error(samples.error());
        frame.eye.insert(frame.eye.end(), samples->begin(), samples->end());
    }
    if (request.method == SppMethod::kReconstruction) {
        RenderSettings corners = settings;
        corners.width = settings.width + 1;
        corners.height = settings.height + 1;
        corners.corner_grid = true;
        Result<std::vector<EyeSample>> samples = eye_samples(renderer, corners);
        if (!samples) return make_error(samples.error());
        frame.corners = std::move(samples).value();
    }
    CutSettings cut;
    cut.criterion = CutCriterion::kBound;
    cut.search = BoundSearch::kHeap;
    cut.error_ratio = settings.error_ratio;
    cut.max_cut = settings.max_cut;
    const SupersampleShading shading = request.method == SppMethod::kReconstruction
                                           ? SupersampleShading::kReconstructionCuts
                                           : SupersampleShading::kPerSampleLightcuts;
    SupersampledImage image;
    const auto start = std::chrono::steady_clock::now();
    const std::vector<glm::dvec3> radiance = shade_supersampled(
        *tree, classic_lights, frame, cut, shading, request.threads, image.cpu);
    image.shading_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    image.shadow_rays = image.cpu.shadow_rays;
    image.hdr = resolve(radiance, frame, image.nonfinite_pixels);
    return image;
}

}  // namespace lc::client
