#include "lightmass_server/indirect/vpl_tracer.h"

#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "lightcuts/seeded_mixer.h"
#include "lightcuts/shading_model.h"
#include "lightmass_server/indirect/photon_emitters.h"
#include "lightmass_server/indirect/surface_sampling.h"
#include "protocol/bake_limits.h"

namespace lc::bake {
namespace {

// Particles per task; the tasks of one batch run in parallel, batches in order
// so progress and cancellation are checked between them.
constexpr uint64_t kParticlesPerTask = 1024;
constexpr uint64_t kTasksPerBatch = 64;

// What every task shares: the lights deposited so far, against the cap.
struct LightQuota {
    std::atomic<uint64_t> made{0};
    std::atomic<bool> exceeded{false};
};

// Follows one particle, appending the lights it deposits. False: stop the
// bake (asked to, or the quota is spent).
bool trace_particle(const SceneGeometry& geometry, const RayCaster& caster, const PhotonEmitters& emitters,
                    const VplOptions& options, float epsilon, uint64_t index, std::vector<IndirectLight>& out,
                    StopPoll& poll, LightQuota& quota) {
    SplitMix64 rng(mix64(options.seed ^ mix64(index + 1)));
    double u[5];
    for (double& x : u) x = rng.uniform();
    Photon photon = emitters.sample(u, options.particle_count);
    glm::vec3 origin = photon.origin;
    glm::vec3 direction = photon.direction;
    glm::vec3 flux = photon.flux;
    for (uint32_t bounce = 1; bounce <= options.bounces; ++bounce) {
        if (poll()) return false;
        auto hit = caster.intersect(origin, direction, 0.0f, std::numeric_limits<float>::infinity());
        if (!hit) return true;
        if (bounce == 1 && photon.range > 0.0f) {
            flux *= float(shading::range_window(double(hit->distance), double(photon.range)));
        }
        const SurfaceTriangle& t = geometry.triangles[hit->triangle];
        glm::vec3 n = front_normal(t);
        if (glm::dot(n, direction) >= 0.0f) return true;
        glm::vec3 albedo =
            t.material < geometry.materials.size() ? bounce_albedo(geometry.materials[t.material]) : glm::vec3(0.0f);
        glm::vec3 reflected = flux * albedo;
        glm::vec3 position = origin + direction * hit->distance;
        if (reflected.x + reflected.y + reflected.z > 0.0f) {
            if (quota.made.fetch_add(1, std::memory_order_relaxed) >= options.max_lights) {
                quota.exceeded.store(true, std::memory_order_relaxed);
                return false;
            }
            out.push_back({position, n, reflected, 0.0f, bounce});
        }
        // Russian roulette on the albedo's largest channel keeps each path's
        // weight bounded; its cap ends paths between white walls too.
        float survive = std::min(float(kVplMaxSurvival), std::max({albedo.x, albedo.y, albedo.z}));
        if (bounce == options.bounces || !(rng.uniform() < double(survive))) return true;
        flux = reflected / survive;
        origin = position + n * epsilon;
        direction = glm::normalize(to_world(tangent_frame(n), cosine_hemisphere(rng.uniform(), rng.uniform())));
    }
    return true;
}

Error quota_error(const VplOptions& options) {
    return make_error("too large: the " + std::to_string(options.particle_count) + " light paths of " +
                          std::to_string(options.bounces) + " bounces leave more than " +
                          std::to_string(options.max_lights) +
                          " VPLs, the limit; ask for fewer paths or bounces",
                      ErrorKind::kRefused);
}

}  // namespace

Result<VplResult> trace_vpls(const SceneGeometry& geometry, const RayCaster& caster,
                             std::span<const SceneLight> lights, const VplOptions& options,
                             const ProgressFn& progress) {
    VplResult result;
    if (options.bounces > kMaxVplBounces) {
        return make_error("VPL bounces " + std::to_string(options.bounces) + " exceed the limit of " +
                          std::to_string(kMaxVplBounces));
    }
    PhotonEmitters emitters(geometry, lights);
    if (emitters.empty() || options.particle_count == 0 || options.bounces == 0) return result;
    result.particles = options.particle_count;
    result.emitted_power = emitters.total_power();
    float epsilon = ray_epsilon(scene_bounds(geometry).extent());

    // Tasks cover this process's share of the paths, in particle order.
    const uint64_t share_begin = std::min(options.particles.begin, options.particle_count);
    const uint64_t share_end = std::clamp(options.particles.end, share_begin, options.particle_count);
    uint64_t task_count = (share_end - share_begin + kParticlesPerTask - 1) / kParticlesPerTask;
    std::vector<std::vector<IndirectLight>> per_task(std::min(task_count, kTasksPerBatch));
    LightQuota quota;
    for (uint64_t first = 0; first < task_count; first += kTasksPerBatch) {
        uint64_t batch = std::min(kTasksPerBatch, task_count - first);
        tbb::parallel_for(uint64_t(0), batch, [&](uint64_t k) {
            std::vector<IndirectLight>& out = per_task[k];
            out.clear();
            StopPoll poll(options.stop);
            uint64_t begin = share_begin + (first + k) * kParticlesPerTask;
            uint64_t end = std::min(share_end, begin + kParticlesPerTask);
            for (uint64_t i = begin; i < end; ++i)
                if (!trace_particle(geometry, caster, emitters, options, epsilon, i, out, poll, quota))
                    return;
        });
        if (quota.exceeded.load()) return quota_error(options);
        if (stop_requested(options.stop)) return options.stop->reason("indirect light tracing");
        for (uint64_t k = 0; k < batch; ++k) {
            result.lights.insert(result.lights.end(), per_task[k].begin(), per_task[k].end());
        }
        double percent = 100.0 * double(first + batch) / double(task_count);
        if (progress && !progress("indirect", percent)) {
            return make_error("indirect light tracing cancelled", ErrorKind::kCancelled);
        }
    }
    return result;
}

}  // namespace lc::bake
