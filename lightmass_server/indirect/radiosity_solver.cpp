#include "lightmass_server/indirect/radiosity_solver.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "lightcuts/shading_model.h"
#include "lightmass_server/indirect/patch_lights.h"
#include "lightmass_server/indirect/photon_emitters.h"
#include "lightmass_server/indirect/point_polygon_form_factor.h"
#include "lightmass_server/indirect/radiosity_parts.h"
#include "lightmass_server/indirect/surface_sampling.h"
#include "protocol/bake_limits.h"

namespace lc::bake {
namespace {

constexpr double kPi = std::numbers::pi;
// Progress at least this often, in steps, besides every whole percent.
constexpr uint64_t kProgressSteps = 256;
// Receivers per parallel chunk: a chunk is a few milliseconds of rays, and
// each chunk first asks whether the bake must stop.
constexpr size_t kPatchesPerChunk = 512;
// Visibility segments stop short of their end point, which sits on the shooter.
constexpr float kSegmentEnd = 1.0f - 1e-4f;

double mean(glm::dvec3 v) { return (v.x + v.y + v.z) / 3.0; }

shading::Emitter emitter_for(const SceneLight& light) {
    shading::Emitter e{};
    e.directional = light.type == LightType::kDirectional;
    e.spot = light.type == LightType::kSpot;
    e.oriented = light.type == LightType::kOriented;
    e.position = glm::dvec3(light.position);
    e.direction = glm::dvec3(light.direction);
    e.range = light.range;
    e.cos_outer = std::cos(double(light.outer_cone_angle));
    e.spot_scale = shading::spot_scale(std::cos(double(light.inner_cone_angle)), e.cos_outer);
    return e;
}

// Points on the shooter the visibility rays aim at: its centre, or the
// centres of its four midpoint triangles.
int visibility_targets(const Patch& p, uint32_t samples, float epsilon, glm::vec3 (&out)[4]) {
    glm::vec3 offset = p.normal * epsilon;
    if (samples < 4) {
        out[0] = p.centre + offset;
        return 1;
    }
    const glm::vec3 (&v)[3] = p.vertices;
    glm::vec3 m01 = 0.5f * (v[0] + v[1]), m12 = 0.5f * (v[1] + v[2]), m20 = 0.5f * (v[2] + v[0]);
    out[0] = (v[0] + m01 + m20) / 3.0f + offset;
    out[1] = (m01 + v[1] + m12) / 3.0f + offset;
    out[2] = (m20 + m12 + v[2]) / 3.0f + offset;
    out[3] = (m01 + m12 + m20) / 3.0f + offset;
    return 4;
}

// What one part knows before a shot: its blocks' unshot power (in block
// order) and its first brightest unshot patch (best_power -1: it has none).
struct PartSummary {
    static constexpr size_t kHeadValues = 5;  // best_power, best, best_unshot; then the blocks
    double best_power = -1.0;
    size_t best = 0;
    glm::dvec3 best_unshot{0.0};
    std::vector<double> block_power;

    std::vector<double> packed() const {
        std::vector<double> out{best_power, double(best), best_unshot.x, best_unshot.y, best_unshot.z};
        out.insert(out.end(), block_power.begin(), block_power.end());
        return out;
    }
    // Reads a part of `blocks` blocks at `at` and moves `at` past it; false if short.
    bool unpack(const std::vector<double>& in, size_t& at, size_t blocks) {
        if (in.size() - std::min(in.size(), at) < kHeadValues + blocks) return false;
        best_power = in[at];
        best = size_t(in[at + 1]);
        best_unshot = {in[at + 2], in[at + 3], in[at + 4]};
        block_power.assign(in.begin() + ptrdiff_t(at + kHeadValues),
                           in.begin() + ptrdiff_t(at + kHeadValues + blocks));
        at += kHeadValues + blocks;
        return true;
    }
};

// The whole solve's next shot: the summed unshot power and the shooter.
struct ShotChoice {
    double unshot_power = 0.0;
    size_t shooter = 0;
    glm::dvec3 shooter_unshot{0.0};
};

// The block sums added in block order and the first of the parts' brightest
// patches, as one pass over every patch in order finds them.
ShotChoice choice_from(const std::vector<PartSummary>& parts) {
    ShotChoice choice;
    double best_power = -1.0;
    for (const PartSummary& part : parts) {
        for (double block : part.block_power) choice.unshot_power += block;
        if (part.best_power > best_power) {
            best_power = part.best_power;
            choice.shooter = part.best;
            choice.shooter_unshot = part.best_unshot;
        }
    }
    return choice;
}

class Solver {
public:
    Solver(const SceneGeometry& geometry, const RayCaster& caster, const RadiosityOptions& options,
           RadiosityResult& result)
        : caster_(caster), options_(options), result_(result), patches_(result.mesh.patches) {
        epsilon_ = ray_epsilon(scene_bounds(geometry).extent());
        size_t n = patches_.size();
        radiosity_.resize(n);
        unshot_.resize(n);
        albedo_.resize(n);
        emission_.resize(n);
        for (size_t j = 0; j < n; ++j) {
            const SurfaceTriangle& t = geometry.triangles[patches_[j].triangle];
            if (t.material >= geometry.materials.size()) continue;
            const SurfaceMaterial& m = geometry.materials[t.material];
            albedo_[j] = glm::dvec3(bounce_albedo(m));
            // A Lambertian emitter of radiance L_e has radiosity pi L_e.
            emission_[j] = kPi * glm::dvec3(m.emission);
            radiosity_[j] = unshot_[j] = emission_[j];
        }
        if (options.parts) part_ = options.parts->part, parts_ = std::max(1u, options.parts->parts);
        receivers_ = radiosity_receivers_of(n, part_, parts_);
        for (uint32_t part = 0; part < parts_; ++part) {
            const IndexRange blocks = radiosity_blocks_of(n, part, parts_);
            summary_sizes_.push_back(int(PartSummary::kHeadValues + (blocks.end - blocks.begin)));
        }
    }

    // f(j) for every receiver this part owns, in parallel chunks that stop
    // early once the bake must stop. The simple partitioner keeps chunks at kPatchesPerChunk (the
    // automatic one hands a thread a large share of two million patches, and
    // a cancel waited 220 ms for it).
    template <class Receiver>
    void for_each_receiver(const Receiver& f) const {
        tbb::parallel_for(
            tbb::blocked_range<size_t>(receivers_.begin, receivers_.end, kPatchesPerChunk),
            [&](const tbb::blocked_range<size_t>& chunk) {
                if (stop_requested(options_.stop)) return;
                for (size_t j = chunk.begin(); j != chunk.end(); ++j) f(j);
            },
            tbb::simple_partitioner());
    }

    // Direct light of a punctual light: E = I G V at each patch centre, reflected at once.
    void shoot_punctual(const SceneLight& light) {
        shading::Emitter e = emitter_for(light);
        glm::dvec3 radiant = glm::dvec3(light.color) * double(light.intensity);
        for_each_receiver([&](size_t j) {
            const Patch& p = patches_[j];
            glm::dvec3 l;
            double g = shading::light_geometry(e, glm::dvec3(p.centre), glm::dvec3(p.normal), l);
            if (!(g > 0.0)) return;
            glm::vec3 origin = p.centre + p.normal * epsilon_;
            bool blocked = light.type == LightType::kDirectional
                               ? caster_.occluded(origin, glm::vec3(l), 0.0f, std::numeric_limits<float>::infinity())
                               : caster_.occluded(origin, light.position - origin, 0.0f, kSegmentEnd);
            if (blocked) return;
            receive(j, albedo_[j] * radiant * g);
        });
    }

    // The unshot power of every patch and the brightest unshot patch, over
    // all the parts (radiosity_parts.h): the same bytes at any part count.
    Result<ShotChoice> choose_shooter() const {
        const PartSummary mine = summarize_own_blocks();
        if (parts_ == 1 || !options_.parts->all_gather) return choice_from({mine});
        Result<std::vector<double>> gathered = options_.parts->all_gather(mine.packed(), summary_sizes_);
        if (!gathered)
            return make_error("radiosity over " + std::to_string(parts_) + " parts: " + gathered.error());
        std::vector<PartSummary> all(parts_);
        size_t at = 0;
        for (uint32_t part = 0; part < parts_; ++part) {
            const IndexRange blocks = radiosity_blocks_of(patches_.size(), part, parts_);
            if (!all[part].unpack(*gathered, at, size_t(blocks.end - blocks.begin)))
                return make_error("radiosity over " + std::to_string(parts_) + " parts: part " +
                                  std::to_string(part) + "'s summary is short");
        }
        if (at != gathered->size()) return make_error("radiosity: the parts' summaries are too long");
        return choice_from(all);
    }

    // Patch i gives its unshot radiosity dB to every patch j that sees it:
    // B_j += rho_j dB F_ji, with F_ji = F(dA_j -> A_i) x visible fraction.
    // The part that owns patch i zeroes its unshot radiosity; every part has
    // dB from the choice.
    void shoot(const ShotChoice& choice) {
        const size_t i = choice.shooter;
        const glm::dvec3 delta = choice.shooter_unshot;
        if (receivers_.contains(i)) unshot_[i] = glm::dvec3(0.0);
        const Patch& shooter = patches_[i];
        glm::dvec3 corners[3] = {glm::dvec3(shooter.vertices[0]), glm::dvec3(shooter.vertices[1]),
                                 glm::dvec3(shooter.vertices[2])};
        glm::vec3 targets[4];
        int target_count = visibility_targets(shooter, options_.visibility_samples, epsilon_, targets);
        for_each_receiver([&](size_t j) {
            if (j == i || !(mean(albedo_[j]) > 0.0)) return;
            const Patch& p = patches_[j];
            // Only the shooter's front side emits.
            if (!(glm::dot(shooter.normal, p.centre - shooter.centre) > 0.0f)) return;
            double f = point_triangle_form_factor(glm::dvec3(p.centre), glm::dvec3(p.normal), corners);
            if (!(f > 0.0)) return;
            glm::vec3 origin = p.centre + p.normal * epsilon_;
            int visible = 0;
            for (int k = 0; k < target_count; ++k) {
                if (!caster_.occluded(origin, targets[k] - origin, 0.0f, kSegmentEnd)) ++visible;
            }
            if (visible > 0) receive(j, albedo_[j] * delta * (f * visible / target_count));
        });
    }

    void finish() {
        // Zero outside this part's receivers.
        result_.radiosity.assign(patches_.size(), glm::vec3(0.0f));
        result_.emission.assign(patches_.size(), glm::vec3(0.0f));
        for (size_t j = receivers_.begin; j < receivers_.end; ++j) {
            const Patch& p = patches_[j];
            result_.radiosity[j] = glm::vec3(radiosity_[j]);
            result_.emission[j] = glm::vec3(emission_[j]);
            glm::dvec3 reflected = radiosity_[j] - emission_[j];
            if (!(mean(reflected) > 0.0)) continue;
            const int levels = near_contact(p, caster_, epsilon_) ? kContactLightLevels : 0;
            append_patch_lights(p, reflected, epsilon_, levels, result_.lights);
        }
    }

    // The power still unshot when the solve stops, spread as an ambient
    // radiosity over the scene (Cohen, Chen, Wallace and Greenberg 1988):
    // ambient = sum(dB_j A_j) / sum(A_j) / (1 - rho_mean), which a closed
    // scene would reflect back and forth; each patch reflects rho_j ambient.
    // Free, unlike a tighter tolerance; it overestimates by the share that
    // leaves an open scene. Summed block by block: the same bytes at any part count.
    Result<glm::dvec3> add_ambient() {
        const IndexRange blocks = radiosity_blocks_of(patches_.size(), part_, parts_);
        std::vector<double> mine;
        for (uint64_t b = blocks.begin; b < blocks.end; ++b) {
            glm::dvec3 sum(0.0);
            const size_t end = std::min<size_t>(patches_.size(), (b + 1) * kRadiosityBlockPatches);
            for (size_t j = b * kRadiosityBlockPatches; j < end; ++j) sum += unshot_[j] * double(patches_[j].area);
            mine.insert(mine.end(), {sum.x, sum.y, sum.z});
        }
        std::vector<double> all = mine;
        if (parts_ > 1 && options_.parts->all_gather) {
            std::vector<int> sizes;
            for (uint32_t part = 0; part < parts_; ++part) {
                const IndexRange theirs = radiosity_blocks_of(patches_.size(), part, parts_);
                sizes.push_back(int(3 * (theirs.end - theirs.begin)));
            }
            Result<std::vector<double>> gathered = options_.parts->all_gather(mine, sizes);
            if (!gathered)
                return make_error("radiosity over " + std::to_string(parts_) + " parts: " + gathered.error());
            all = std::move(gathered).value();
        }
        glm::dvec3 unshot_power(0.0), reflectance(0.0);
        for (size_t k = 0; k + 2 < all.size(); k += 3) unshot_power += glm::dvec3(all[k], all[k + 1], all[k + 2]);
        double area = 0.0;
        for (size_t j = 0; j < patches_.size(); ++j) {
            area += double(patches_[j].area);
            reflectance += albedo_[j] * double(patches_[j].area);
        }
        if (!(area > 0.0)) return glm::dvec3(0.0);
        const glm::dvec3 rho_mean = glm::min(reflectance / area, glm::dvec3(0.999));
        const glm::dvec3 ambient = unshot_power / area / (glm::dvec3(1.0) - rho_mean);
        for (size_t j = receivers_.begin; j < receivers_.end; ++j) radiosity_[j] += albedo_[j] * ambient;
        return ambient;
    }

private:
    // One part's blocks' unshot power, block by block, and its first brightest patch.
    PartSummary summarize_own_blocks() const {
        PartSummary summary;
        const IndexRange blocks = radiosity_blocks_of(patches_.size(), part_, parts_);
        for (uint64_t b = blocks.begin; b < blocks.end; ++b) {
            double sum = 0.0;
            const size_t end = std::min<size_t>(patches_.size(), (b + 1) * kRadiosityBlockPatches);
            for (size_t j = b * kRadiosityBlockPatches; j < end; ++j) {
                const double power = mean(unshot_[j]) * double(patches_[j].area);
                sum += power;
                if (power > summary.best_power) summary.best_power = power, summary.best = j;
            }
            summary.block_power.push_back(sum);
        }
        if (summary.best_power >= 0.0) summary.best_unshot = unshot_[summary.best];
        return summary;
    }

    void receive(size_t j, glm::dvec3 reflected) {
        radiosity_[j] += reflected;
        unshot_[j] += reflected;
    }

    const RayCaster& caster_;
    const RadiosityOptions& options_;
    RadiosityResult& result_;
    const std::vector<Patch>& patches_;
    float epsilon_ = 0.0f;
    uint32_t part_ = 0, parts_ = 1;
    IndexRange receivers_;  // the patches this part updates
    std::vector<int> summary_sizes_;  // each part's packed PartSummary, in doubles
    std::vector<glm::dvec3> radiosity_, unshot_, albedo_, emission_;
};

std::string percent_text(double fraction) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g%%", 100.0 * fraction);
    return text;
}

}  // namespace

Result<RadiosityResult> solve_radiosity(const SceneGeometry& geometry, const RayCaster& caster,
                                        std::span<const SceneLight> lights, const RadiosityOptions& options,
                                        const ProgressFn& progress) {
    if (!(options.tolerance >= 0.0 && options.tolerance < 1.0)) {
        return make_error("radiosity tolerance must be in [0, 1), got " + readable_number(options.tolerance));
    }
    auto start = std::chrono::steady_clock::now();
    auto seconds = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    RadiosityResult result;
    auto mesh = make_patches(geometry, options.patch_size, options.max_patches, options.stop);
    if (!mesh.ok()) return mesh.failure();
    result.mesh = std::move(mesh).value();
    Solver solver(geometry, caster, options, result);
    for (const SceneLight& light : lights) {
        solver.shoot_punctual(light);
        if (stop_requested(options.stop)) return options.stop->reason("radiosity");
    }

    Result<ShotChoice> choice = solver.choose_shooter();
    if (!choice) return choice.failure();
    const double total = choice->unshot_power;
    double unshot = total;
    double reported = -1.0;
    while (total > 0.0) {
        double shot = std::clamp(1.0 - unshot / total, 0.0, 1.0);
        if (std::floor(100.0 * shot) > std::floor(100.0 * reported) || result.steps % kProgressSteps == 0) {
            reported = std::max(reported, shot);
            result.convergence.push_back({result.steps, seconds(), shot});
            if (progress && !progress("radiosity", 100.0 * reported)) {
                return make_error("radiosity cancelled", ErrorKind::kCancelled);
            }
        }
        if (unshot <= options.tolerance * total) break;
        if (result.steps >= options.max_steps) {
            result.converged = false;
            result.message = "radiosity stopped after its budget of " + std::to_string(options.max_steps) +
                             " steps with " + percent_text(unshot / total) + " of the power unshot (tolerance " +
                             percent_text(options.tolerance) +
                             "); the indirect light is too dark by about that much: raise the step budget or the "
                             "tolerance, or lower the reflectances";
            break;
        }
        solver.shoot(*choice);
        if (stop_requested(options.stop)) return options.stop->reason("radiosity");
        ++result.steps;
        choice = solver.choose_shooter();
        if (!choice) return choice.failure();
        unshot = choice->unshot_power;
    }
    result.unshot_fraction = total > 0.0 ? unshot / total : 0.0;
    result.convergence.push_back({result.steps, seconds(), 1.0 - result.unshot_fraction});
    Result<glm::dvec3> ambient = solver.add_ambient();
    if (!ambient) return ambient.failure();
    result.ambient = *ambient;
    solver.finish();
    return result;
}

}  // namespace lc::bake
