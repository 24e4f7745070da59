// Reference-mode throughput on the GPU: light evaluations per second of the
// renderer's lighting pass at 512x512 with 1,024 and 16,384 point lights,
// next to a minimal kernel that runs only the light loop (same light layout,
// same workgroup size) in the same process. scripts/bench/render.sh runs it
// and writes docs/bench/render_throughput.csv.
//
// The scene is the generated room written to glTF and read back through the
// loader, and every pixel sees geometry. Rates are computed from the CPU wall
// clock around submit-and-wait (for the renderer that is the whole frame, so
// its rate is a lower bound) and, as a second column, from GPU timestamps:
// lavapipe takes a timestamp lazily while a render target from an earlier
// raster pass is still bound, so timestamps alone misreport a compute-only
// dispatch that follows a renderer frame.
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>

#include "lightcuts/tree/gpu_layout.h"
#include "editor_client/render/renderer.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "editor_client/vk/barriers.h"
#include "editor_client/vk/buffer.h"
#include "editor_client/vk/compute_pipeline.h"
#include "editor_client/vk/context.h"
#include "editor_client/vk/descriptor_set.h"
#include "editor_client/vk/image.h"
#include "editor_client/vk/pipeline_layout.h"
#include "editor_client/vk/timestamp_query_pool.h"
#include "light_loop_minimal_comp.spv.h"

namespace lc::client {
namespace {

constexpr uint32_t kSize = 512;
constexpr uint32_t kWorkgroup = 8;

// Null when the machine has no usable Vulkan device.
vk::Context* context() {
    static std::unique_ptr<vk::Context> ctx = [] {
        Result<vk::Context> c = vk::Context::create({});
        if (!c) {
            std::fprintf(stderr, "no Vulkan device: %s\n", c.error().c_str());
            return std::unique_ptr<vk::Context>();
        }
        return std::make_unique<vk::Context>(std::move(c).value());
    }();
    return ctx.get();
}

std::vector<SceneLight> room_lights(uint32_t count) {
    LightLayoutOptions layout;
    layout.count = count;
    layout.seed = 1;
    layout.type = LightTypeChoice::kPoint;
    layout.box_min = kRoomLightBoxMin;
    layout.box_max = kRoomLightBoxMax;
    layout.intensity = 10.0f / float(count);
    Result<std::vector<SceneLight>> lights = generate_lights(layout);
    return lights ? *lights : std::vector<SceneLight>{};
}

// The room with `count` point lights, through a glTF file and the loader.
Result<Scene> load_room(uint32_t count) {
    Scene room = make_room_scene();
    room.lights = room_lights(count);
    std::filesystem::path path = std::filesystem::temp_directory_path() /
                                 ("lc-bench-room-" + std::to_string(count) + ".gltf");
    Status written = write_scene_gltf(room, path);
    if (!written) return make_error(written.error());
    Result<Scene> scene = load_scene(path);
    std::filesystem::remove(path);
    return scene;
}

void BM_ReferenceLightingPass(benchmark::State& state) {
    const uint32_t count = uint32_t(state.range(0));
    if (context() == nullptr) {
        state.SkipWithError("no Vulkan device");
        return;
    }
    Result<Scene> scene = load_room(count);
    if (!scene) {
        state.SkipWithError(scene.error().c_str());
        return;
    }
    Result<std::unique_ptr<Renderer>> renderer = Renderer::create(*context(), *scene, nullptr);
    if (!renderer) {
        state.SkipWithError(renderer.error().c_str());
        return;
    }
    RenderSettings settings;
    settings.width = settings.height = kSize;
    settings.camera = camera_from_scene(scene->cameras.at(0));
    // Warm-up frame: pipelines and targets are built outside the timing.
    if (Result<RenderStats> warm = (*renderer)->render(settings); !warm) {
        state.SkipWithError(warm.error().c_str());
        return;
    }
    double lighting_ms = 0.0, render_ms = 0.0, wall_ms = 0.0;
    uint64_t evaluations = 0, geometry_pixels = 0;
    for (auto _ : state) {
        Result<RenderStats> stats = (*renderer)->render(settings);
        if (!stats) {
            state.SkipWithError(stats.error().c_str());
            return;
        }
        state.SetIterationTime(stats->timing.wall_ms * 1e-3);
        lighting_ms += stats->timing.lighting_ms;
        render_ms += stats->timing.render_ms;
        wall_ms += stats->timing.wall_ms;
        evaluations += stats->cuts.light_evaluations;
        geometry_pixels = stats->geometry_pixels;
    }
    const double n = double(state.iterations());
    state.counters["lights"] = count;
    state.counters["pixels"] = double(geometry_pixels);
    state.counters["lighting_ms"] = lighting_ms / n;
    state.counters["render_ms"] = render_ms / n;
    state.counters["wall_ms"] = wall_ms / n;
    state.counters["evals_per_s"] = double(evaluations) / (wall_ms * 1e-3);
    state.counters["evals_per_s_gpu"] = double(evaluations) / (lighting_ms * 1e-3);
}

// The minimal kernel: one storage buffer of GpuLight, one output image.
void BM_MinimalLightLoop(benchmark::State& state) {
    const uint32_t count = uint32_t(state.range(0));
    if (context() == nullptr) {
        state.SkipWithError("no Vulkan device");
        return;
    }
    const vk::Device& device = context()->device();
    VkDevice dev = device.handle();
    std::vector<GpuLight> lights;
    for (const SceneLight& l : room_lights(count)) lights.push_back(make_gpu_light(l));
    auto light_buffer = vk::Buffer::create_with_data(device, context()->command_pool(),
                                                     std::as_bytes(std::span(lights)),
                                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    auto image = vk::Image::create(
        device, {kSize, kSize, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
    std::array<VkDescriptorSetLayoutBinding, 2> bindings{};
    bindings[0] = {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    bindings[1] = {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    auto set_layout = vk::DescriptorSetLayout::create(dev, bindings);
    std::array<VkDescriptorPoolSize, 2> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
    auto pool = vk::DescriptorPool::create(dev, 1, sizes);
    if (!light_buffer || !image || !set_layout || !pool) {
        state.SkipWithError("cannot create the minimal kernel's resources");
        return;
    }
    Result<VkDescriptorSet> set = pool->allocate(*set_layout);
    if (!set) {
        state.SkipWithError(set.error().c_str());
        return;
    }
    vk::DescriptorWriter(*set)
        .storage_buffer(0, light_buffer->handle())
        .storage_image(1, image->view())
        .update(dev);
    struct Constants {
        uint32_t width, height, light_count;
        float extent;
    } constants{kSize, kSize, count, 10.0f};
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(Constants)};
    VkDescriptorSetLayout layout_handle = set_layout->handle();
    auto layout =
        vk::PipelineLayout::create(dev, std::span(&layout_handle, 1), std::span(&range, 1));
    vk::Specialization spec;
    spec.set_uint(0, kWorkgroup).set_uint(1, kWorkgroup);
    auto pipeline = layout ? vk::ComputePipeline::create(
                                 dev, layout->handle(),
                                 std::span<const uint32_t>(light_loop_minimal_comp_spv), spec)
                           : Result<vk::ComputePipeline>(make_error("no layout"));
    auto timestamps = vk::TimestampQueryPool::create(device, 2);
    if (!pipeline || !timestamps) {
        state.SkipWithError("cannot create the minimal kernel's pipeline");
        return;
    }
    // GPU milliseconds of the dispatch (timestamps); wall_ms gets the CPU view.
    double wall_ms = 0.0;
    auto dispatch = [&]() -> Result<double> {
        auto start = std::chrono::steady_clock::now();
        Status run = context()->command_pool().run_one_time(device, [&](VkCommandBuffer cmd) {
            vk::transition_image(
                cmd,
                {image->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT});
            timestamps->reset(cmd);
            timestamps->write(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, 0);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->handle());
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout->handle(), 0, 1,
                                    &*set, 0, nullptr);
            vkCmdPushConstants(cmd, layout->handle(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                               sizeof(constants), &constants);
            vkCmdDispatch(cmd, kSize / kWorkgroup, kSize / kWorkgroup, 1);
            timestamps->write(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 1);
        });
        if (!run) return make_error(run.error());
        wall_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        Result<std::vector<double>> ms = timestamps->read_ms();
        if (!ms) return make_error(ms.error());
        return (*ms)[1];
    };
    if (Result<double> warm = dispatch(); !warm) {
        state.SkipWithError(warm.error().c_str());
        return;
    }
    double total_gpu_ms = 0.0, total_wall_ms = 0.0;
    for (auto _ : state) {
        Result<double> ms = dispatch();
        if (!ms) {
            state.SkipWithError(ms.error().c_str());
            return;
        }
        state.SetIterationTime(wall_ms * 1e-3);
        total_gpu_ms += *ms;
        total_wall_ms += wall_ms;
    }
    const double n = double(state.iterations());
    const double evaluations = double(kSize) * kSize * count * n;
    state.counters["lights"] = count;
    state.counters["pixels"] = double(kSize) * kSize;
    state.counters["lighting_ms"] = total_gpu_ms / n;
    state.counters["wall_ms"] = total_wall_ms / n;
    state.counters["evals_per_s"] = evaluations / (total_wall_ms * 1e-3);
    state.counters["evals_per_s_gpu"] = evaluations / (total_gpu_ms * 1e-3);
}

// Each configuration runs a fixed number of frames (16,384 lights take
// seconds per frame on lavapipe).
BENCHMARK(BM_MinimalLightLoop)
    ->Arg(1024)
    ->Iterations(5)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReferenceLightingPass)
    ->Arg(1024)
    ->Iterations(5)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MinimalLightLoop)
    ->Arg(16384)
    ->Iterations(2)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReferenceLightingPass)
    ->Arg(16384)
    ->Iterations(2)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lc::client

BENCHMARK_MAIN();
