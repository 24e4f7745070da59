#include "lightmass_server/mpi/rank/rank_bake.h"

#include <cstdio>
#include <string>

#include "lightcuts/status_macros.h"
#include "lightmass_server/emitters/area_light_sampler.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/index_range.h"
#include "lightmass_server/indirect/radiosity_parts.h"
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

// The census lines and warnings rank 0 reports, as run_bake reports them.
struct BakeNotes {
    std::vector<std::string> effects, warnings;
};

// This rank's area-light samples, gathered on rank 0 (the whole set there).
Result<std::vector<SceneLight>> area_lights(const RankJob& job, const Share& share, RankStats& stats,
                                            BakeNotes& notes) {
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
    if (all && share.root() && counted->budget_raised) {
        notes.warnings.push_back("--area-lights " + std::to_string(budget) + " is below the " +
                                 std::to_string(counted->emissive_triangles) +
                                 " emissive triangles: one sample each");
    }
    if (all && share.root() && !all->empty()) {
        notes.effects.push_back("area lights: simulated (" + std::to_string(counted->emissive_triangles) +
                                " emissive triangles, " + std::to_string(all->size()) + " samples, " +
                                std::to_string(share.ranks) + " ranks)");
    }
    return all;
}

// "indirect: ..." for the whole bake, on rank 0: the counts over every rank.
std::string indirect_census(const IndirectOptions& options, const IndirectStageResult& stage, size_t lights,
                            int ranks) {
    if (stage.census.rfind("skipped", 0) == 0) return "indirect: " + stage.census;
    const std::string over = std::to_string(ranks) + " ranks)";
    if (options.method == IndirectMethod::kRadiosity)  // patches, steps and unshot power are global
        return "indirect: " + stage.census.substr(0, stage.census.rfind(')')) + ", " + over;
    char text[160];
    std::snprintf(text, sizeof text, "indirect: simulated (%zu VPLs from %llu particles, %u bounces, ",
                  lights, static_cast<unsigned long long>(options.vpl.particle_count), options.vpl.bounces);
    return text + over;
}

// The bounced light, split over the ranks: the VPL paths by index range, the
// radiosity's receivers by patch blocks (radiosity_parts.h, one all-gather a
// shot). Rank 0 gathers the lights in rank order: the one-process lights.
Result<std::vector<IndirectLight>> indirect_lights(const RankJob& job, const Share& share,
                                                   const RayCaster* caster,
                                                   std::span<const SceneLight> sources,
                                                   const ProgressFn& progress, RankStats& stats,
                                                   BakeNotes& notes) {
    IndirectOptions options = indirect_options(job.request.indirect, job.request.seed);
    const RadiosityParts parts{uint32_t(share.rank), uint32_t(share.ranks),
                               [&stats](const std::vector<double>& mine,
                                        const std::vector<int>& sizes) -> Result<std::vector<double>> {
                                   return all_gather_known_sizes(mine, sizes, stats.bytes_sent);
                               }};
    if (options.method == IndirectMethod::kVpl)
        options.vpl.particles =
            share_of(options.vpl.particle_count, uint32_t(share.rank), uint32_t(share.ranks));
    options.radiosity.parts = &parts;
    const SceneGeometry no_geometry;
    Result<IndirectStageResult> stage =
        run_indirect_stage(job.geometry ? *job.geometry : no_geometry, caster, sources, options,
                           share.root() ? progress : ProgressFn{});
    if (!stage) return stage.failure();
    stats.lights_made += stage->lights.size();
    Result<std::vector<IndirectLight>> all = gather_in_rank_order(stage->lights, stats.bytes_sent);
    if (!all || !share.root()) return all;
    // The same cap as a bake in one process (bake_footprint.h), over all the ranks' paths together.
    if (options.method == IndirectMethod::kVpl && all->size() > kMaxIndirectLights) {
        return make_error("too large: the " + std::to_string(options.vpl.particle_count) +
                              " light paths of " + std::to_string(options.vpl.bounces) + " bounces leave " +
                              std::to_string(all->size()) + " VPLs over " + std::to_string(share.ranks) +
                              " ranks, more than the limit of " + std::to_string(kMaxIndirectLights) +
                              "; ask for fewer paths or bounces",
                          ErrorKind::kRefused);
    }
    notes.effects.push_back(indirect_census(options, *stage, all->size(), share.ranks));
    notes.warnings.insert(notes.warnings.end(), stage->warnings.begin(), stage->warnings.end());
    return all;
}

}  // namespace

Result<std::optional<BuildResult>> bake_share(const RankJob& job, int rank, int ranks,
                                              const ProgressFn& progress, RankStats& stats) {
    const Share share{rank, ranks};
    BakeNotes notes;
    std::vector<SceneLight> lights = job.lights;  // the tree's input order: scene, area, sky, bounces
    std::optional<RayCaster> caster;
    if (job.geometry) {
        Result<RayCaster> built = RayCaster::build(*job.geometry, 1);
        if (!built) return make_error("ray caster: " + built.error());
        caster.emplace(std::move(built.value()));
        Result<std::vector<SceneLight>> area = area_lights(job, share, stats, notes);
        if (!area) return area.failure();
        lights.insert(lights.end(), area->begin(), area->end());
    }
    if (notes.effects.empty()) notes.effects.push_back("area lights: skipped: no drawn triangle emits power");
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
        notes.effects.push_back(ranks == 1 ? sampled->census
                                           : sampled->census.substr(0, sampled->census.find(':')) +
                                                 ": simulated (" + std::to_string(sky.size()) +
                                                 " lights over " + std::to_string(ranks) + " ranks)");
    }
    std::vector<SceneLight> sources = job.lights;
    if (job.request.indirect.method != IndirectMethod::kOff)
        sources.insert(sources.end(), sky.begin(), sky.end());
    Result<std::vector<IndirectLight>> bounced =
        indirect_lights(job, share, caster ? &*caster : nullptr, sources, progress, stats, notes);
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
    built->report.effects = std::move(notes.effects);
    built->report.warnings.insert(built->report.warnings.begin(), notes.warnings.begin(),
                                  notes.warnings.end());
    return std::optional<BuildResult>(std::move(built.value()));
}

}  // namespace lc::bake
