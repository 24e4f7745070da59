#include "lightmass_server/mpi/rank/rank_bake.h"

#include <cstdio>
#include <string>

#include "lightcuts/status_macros.h"
#include "lightmass_server/emitters/area_light_sampler.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/index_range.h"
#include "lightmass_server/mpi/rank/mpi_transfer.h"
#include "lightmass_server/mpi/rank/remote_subtrees.h"
#include "lightmass_server/raycast/ray_caster.h"
#include "protocol/bake_limits.h"

namespace lc::bake {
namespace {

struct Share {
    int rank = 0, ranks = 1;
    bool root() const { return rank == 0; }
};

// This rank's area-light samples, gathered on rank 0 (the whole set there).
Result<std::vector<SceneLight>> area_lights(const RankJob& job, const Share& share, RankStats& stats,
                                            std::vector<std::string>& effects) {
    const uint32_t budget = job.request.area_lights != 0 ? job.request.area_lights : kDefaultAreaLights;
    const uint64_t seed = job.request.seed;
    // The samples' count: the budget, raised to one per emissive triangle.
    Result<AreaLightSampling> counted = sample_area_lights(*job.geometry, budget, seed, IndexRange{0, 0});
    if (!counted) return make_error("area lights: " + counted.error());
    const uint64_t total = std::max<uint64_t>(budget, counted->emissive_triangles);
    IndexRange mine = share_of(total, uint32_t(share.rank), uint32_t(share.ranks));
    if (share.rank + 1 == share.ranks) mine.end = IndexRange{}.end;  // the last share takes any rounding up
    Result<AreaLightSampling> sampled = sample_area_lights(*job.geometry, budget, seed, mine);
    if (!sampled) return make_error("area lights: " + sampled.error());
    stats.lights_made += sampled->lights.size();
    Result<std::vector<SceneLight>> all = gather_in_rank_order(sampled->lights, stats.bytes_sent);
    if (all && share.root() && !all->empty()) {
        effects.push_back("area lights: simulated (" + std::to_string(counted->emissive_triangles) +
                          " emissive triangles, " + std::to_string(all->size()) + " samples, " +
                          std::to_string(share.ranks) + " ranks)");
    }
    return all;
}

// The bounced light: VPL paths split over the ranks; radiosity on rank 0 alone.
Result<std::vector<IndirectLight>> indirect_lights(const RankJob& job, const Share& share,
                                                   const RayCaster* caster,
                                                   std::span<const SceneLight> sources,
                                                   const ProgressFn& progress, RankStats& stats,
                                                   std::vector<std::string>& effects) {
    IndirectOptions options = indirect_options(job.request.indirect, job.request.seed);
    const bool split = options.method == IndirectMethod::kVpl;
    if (split)
        options.vpl.particles =
            share_of(options.vpl.particle_count, uint32_t(share.rank), uint32_t(share.ranks));
    if (!split && !share.root()) return std::vector<IndirectLight>{};
    const SceneGeometry no_geometry;
    Result<IndirectStageResult> stage =
        run_indirect_stage(job.geometry ? *job.geometry : no_geometry, caster, sources, options,
                           share.root() ? progress : ProgressFn{});
    if (!stage) return stage.failure();
    if (!split) {
        effects.push_back("indirect: " + stage->census);
        return std::move(stage->lights);
    }
    stats.lights_made += stage->lights.size();
    Result<std::vector<IndirectLight>> all = gather_in_rank_order(stage->lights, stats.bytes_sent);
    // The same cap as a bake in one process (bake_footprint.h), over all the ranks' paths together.
    if (all && share.root() && all->size() > kMaxIndirectLights) {
        return make_error("too large: the " + std::to_string(options.vpl.particle_count) +
                              " light paths of " + std::to_string(options.vpl.bounces) + " bounces leave " +
                              std::to_string(all->size()) + " VPLs over " + std::to_string(share.ranks) +
                              " ranks, more than the limit of " + std::to_string(kMaxIndirectLights) +
                              "; ask for fewer paths or bounces",
                          ErrorKind::kRefused);
    }
    if (all && share.root()) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "indirect: simulated (%zu VPLs from %llu particles, %u bounces, %d ranks)", all->size(),
                      static_cast<unsigned long long>(options.vpl.particle_count), options.vpl.bounces,
                      share.ranks);
        effects.push_back(text);
    }
    return all;
}

}  // namespace

Result<std::optional<BuildResult>> bake_share(const RankJob& job, int rank, int ranks,
                                              const ProgressFn& progress, RankStats& stats) {
    const Share share{rank, ranks};
    std::vector<std::string> effects;
    std::vector<SceneLight> lights = job.lights;  // the tree's input order: scene, area, sky, bounces
    std::optional<RayCaster> caster;
    if (job.geometry) {
        Result<RayCaster> built = RayCaster::build(*job.geometry, 1);
        if (!built) return make_error("ray caster: " + built.error());
        caster.emplace(std::move(built.value()));
        Result<std::vector<SceneLight>> area = area_lights(job, share, stats, effects);
        if (!area) return area.failure();
        lights.insert(lights.end(), area->begin(), area->end());
    }
    if (effects.empty()) effects.push_back("area lights: skipped: no drawn triangle emits power");
    // The sky's strata split over the ranks; every rank gets them all back:
    // the photons leave the sky too.
    std::vector<SceneLight> sky;
    if (job.environment) {
        Result<EnvironmentLights> sampled =
            sample_environment(*job.environment, job.request.environment_lights, job.request.seed,
                               uint32_t(rank), uint32_t(ranks));
        if (!sampled) return sampled.failure();
        stats.lights_made += sampled->lights.size();
        Result<std::vector<SceneLight>> all = gather_to_all(sampled->lights, stats.bytes_sent);
        if (!all) return all.failure();
        sky = std::move(all.value());
        effects.push_back(ranks == 1 ? sampled->census
                                     : sampled->census.substr(0, sampled->census.find(':')) +
                                           ": simulated (" + std::to_string(sky.size()) + " lights over " +
                                           std::to_string(ranks) + " ranks)");
    }
    std::vector<SceneLight> sources = job.lights;
    if (job.request.indirect.method != IndirectMethod::kOff)
        sources.insert(sources.end(), sky.begin(), sky.end());
    Result<std::vector<IndirectLight>> bounced =
        indirect_lights(job, share, caster ? &*caster : nullptr, sources, progress, stats, effects);
    if (!bounced) return bounced.failure();
    if (!share.root()) {
        LC_RETURN_IF_ERROR(serve_subtrees(job_build_options(job.request), stats));
        return std::optional<BuildResult>{};
    }

    // Each stage's vector goes as soon as it is copied: rank 0 holds the whole set.
    std::vector<SceneLight> tree_bounced = as_tree_lights(*bounced);
    bounced->clear();
    bounced->shrink_to_fit();
    lights.reserve(lights.size() + sky.size() + tree_bounced.size());
    lights.insert(lights.end(), sky.begin(), sky.end());
    lights.insert(lights.end(), tree_bounced.begin(), tree_bounced.end());
    tree_bounced = {};
    BuildOptions options = job_build_options(job.request);
    // An LBVH's subtrees go to the ranks (the same tree at any rank count).
    const LbvhRemoteMerges remote = subtrees_over_ranks(ranks, lights);
    if (options.builder == BuilderKind::kLbvh && ranks > 1) options.lbvh_remote = &remote;
    Result<BuildResult> built = build_light_tree(lights, options, progress);
    end_subtree_service(ranks);
    if (!built) return built.failure();
    built->report.effects = std::move(effects);
    return std::optional<BuildResult>(std::move(built.value()));
}

}  // namespace lc::bake
