#include "lightmass_server/mpi/rank/rank_bake.h"

#include <cstdio>
#include <string>

#include "lightcuts/status_macros.h"
#include "lightmass_server/emitters/area_light_sampler.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/builders/index_range.h"
#include "lightmass_server/indirect/radiosity_parts.h"
#include "lightmass_server/indirect/vpl_tracer.h"
#include "lightmass_server/mpi/rank/mpi_transfer.h"
#include "lightmass_server/mpi/rank/split_lbvh.h"
#include "lightmass_server/raycast/ray_caster.h"
#include "protocol/bake_limits.h"

namespace lc::bake {
namespace {

namespace fs = std::filesystem;

struct Share {
    int rank = 0, ranks = 1;
    bool root() const { return rank == 0; }
};

// The census lines and warnings rank 0 reports, as run_bake reports them.
struct BakeNotes {
    std::vector<std::string> effects, warnings;
    TreeLightCounts lights;  // over every rank
};

// Lights one rank made: its own share (index: where it sits among all the
// ranks'), or, gathered, the whole set on rank 0.
template <typename T>
struct MadeLights {
    std::vector<T> lights;
    ShareIndex index;
};

// This rank's area-light samples, gathered on rank 0 when `gather`.
Result<MadeLights<SceneLight>> area_lights(const RankJob& job, const Share& share, bool gather,
                                           RankStats& stats, BakeNotes& notes) {
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
    const ShareIndex index = index_of_share(sampled->lights.size());
    Result<std::vector<SceneLight>> all =
        gather ? gather_in_rank_order(sampled->lights, stats.bytes_sent) : std::move(sampled->lights);
    if (all && share.root() && counted->budget_raised) {
        notes.warnings.push_back("--area-lights " + std::to_string(budget) + " is below the " +
                                 std::to_string(counted->emissive_triangles) +
                                 " emissive triangles: one sample each");
    }
    if (all && share.root() && index.total != 0) {
        notes.effects.push_back("area lights: simulated (" + std::to_string(counted->emissive_triangles) +
                                " emissive triangles, " + std::to_string(index.total) + " samples, " +
                                std::to_string(share.ranks) + " ranks)");
    }
    if (!all) return all.failure();
    return MadeLights<SceneLight>{std::move(all.value()), gather ? ShareIndex{0, index.total} : index};
}

// "indirect: ..." for the whole bake, on rank 0: the counts over every rank.
std::string indirect_census(const IndirectOptions& options, const IndirectStageResult& stage, size_t lights,
                            int ranks) {
    if (stage.census.rfind("skipped", 0) == 0) return "indirect: " + stage.census;
    const std::string over = std::to_string(ranks) + " ranks)";
    if (options.method == IndirectMethod::kRadiosity)  // patches, steps and unshot power are global
        return "indirect: " + stage.census.substr(0, stage.census.rfind(')')) + ", " + over;
    // The default follows paths until Russian roulette ends them: no count to print.
    const std::string bounces = options.vpl.bounces < kMaxVplBounces
                                    ? std::to_string(options.vpl.bounces) + " bounces"
                                    : std::string("all bounces until Russian roulette");
    char text[160];
    std::snprintf(text, sizeof text, "indirect: simulated (%zu VPLs from %llu particles, %s, ", lights,
                  static_cast<unsigned long long>(options.vpl.particle_count), bounces.c_str());
    return text + over;
}

// The bounced light, split over the ranks: the VPL paths by index range, the
// radiosity's receivers by patch blocks (radiosity_parts.h, one all-gather a
// shot). When `gather`, rank 0 gathers the lights in rank order: the
// one-process lights. Without the gather (an LBVH built over the ranks) no
// rank holds them all, so the VPLs' cap is the tree's own limit.
Result<MadeLights<IndirectLight>> indirect_lights(const RankJob& job, const Share& share,
                                                  const RayCaster* caster,
                                                  std::span<const SceneLight> sources, bool gather,
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
    const uint64_t cap = gather ? kMaxIndirectLights : kMaxRankBakeIndirectLights;
    options.vpl.max_lights = cap;
    const SceneGeometry no_geometry;
    Result<IndirectStageResult> stage =
        run_indirect_stage(job.geometry ? *job.geometry : no_geometry, caster, sources, options,
                           share.root() ? progress : ProgressFn{});
    if (!stage) return stage.failure();
    stats.lights_made += stage->lights.size();
    const ShareIndex index = index_of_share(stage->lights.size());
    // The cap over all the ranks' paths together (every rank sees the same total).
    if (options.method == IndirectMethod::kVpl && index.total > cap) {
        return make_error("too large: the " + std::to_string(options.vpl.particle_count) +
                              " light paths of " + std::to_string(options.vpl.bounces) + " bounces leave " +
                              std::to_string(index.total) + " VPLs over " + std::to_string(share.ranks) +
                              " ranks, more than the limit of " + std::to_string(cap) +
                              "; ask for fewer paths or bounces",
                          ErrorKind::kRefused);
    }
    if (share.root()) {
        notes.effects.push_back(indirect_census(options, *stage, index.total, share.ranks));
        notes.warnings.insert(notes.warnings.end(), stage->warnings.begin(), stage->warnings.end());
    }
    if (!gather) return MadeLights<IndirectLight>{std::move(stage->lights), index};
    Result<std::vector<IndirectLight>> all = gather_in_rank_order(stage->lights, stats.bytes_sent);
    if (!all) return all.failure();
    return MadeLights<IndirectLight>{std::move(all.value()), ShareIndex{0, index.total}};
}

// "lbvh over N ranks (rank 0's clock): spread and merge X ms, ..."
std::string phase_census(const BuildReport& report, int ranks) {
    std::string text = "lbvh over " + std::to_string(ranks) + " ranks (rank 0's clock):";
    for (const BuildPhase& phase : report.phases)
        text +=
            (text.back() == ':' ? " " : ", ") + phase.name + " " + std::to_string(int64_t(phase.ms)) + " ms";
    return text;
}

// This rank's lights with their indices in the tree's input order (scene,
// area, sky, bounces): rank 0 adds the scene's and the sky's, which every
// rank holds.
OwnedLights owned_lights(const RankJob& job, const Share& share, MadeLights<SceneLight> area,
                         const std::vector<SceneLight>& sky, MadeLights<IndirectLight> bounced, BakeNotes& notes) {
    OwnedLights owned;
    const uint64_t scene = job.lights.size();
    const auto add = [&owned](std::vector<SceneLight>& lights, uint64_t first) {
        for (size_t i = 0; i < lights.size(); ++i) owned.index.push_back(uint32_t(first + i));
        owned.lights.insert(owned.lights.end(), lights.begin(), lights.end());
        lights = {};
    };
    std::vector<SceneLight> mine = share.root() ? job.lights : std::vector<SceneLight>{};
    add(mine, 0);
    add(area.lights, scene + area.index.before);
    mine = share.root() ? sky : std::vector<SceneLight>{};
    add(mine, scene + area.index.total);
    // GUIDs from the VPLs' indices over all ranks; dark VPLs drop out, so the
    // tree's indices come from the kept ones' counts.
    std::vector<SceneLight> tree_bounced = as_tree_lights(bounced.lights, bounced.index.before);
    bounced.lights = {};
    const ShareIndex kept = index_of_share(tree_bounced.size());
    notes.lights.add_bounced(job.request.indirect.method, kept.total);
    add(tree_bounced, scene + area.index.total + sky.size() + kept.before);
    return owned;
}

// Rank 0 gathered every light: it builds the tree with any builder and writes it.
Result<BuildResult> build_on_rank_zero(const RankJob& job, const MadeLights<SceneLight>& area,
                                       const std::vector<SceneLight>& sky, MadeLights<IndirectLight> bounced,
                                       const ProgressFn& progress, BakeNotes& notes) {
    std::vector<SceneLight> lights = job.lights;
    std::vector<SceneLight> tree_bounced = as_tree_lights(bounced.lights);
    notes.lights.add_bounced(job.request.indirect.method, tree_bounced.size());
    bounced.lights = {};
    lights.reserve(lights.size() + area.lights.size() + sky.size() + tree_bounced.size());
    lights.insert(lights.end(), area.lights.begin(), area.lights.end());
    lights.insert(lights.end(), sky.begin(), sky.end());
    lights.insert(lights.end(), tree_bounced.begin(), tree_bounced.end());
    tree_bounced = {};
    return build_light_tree(lights, job_build_options(job.request), progress);
}

}  // namespace

Result<std::optional<BuildResult>> bake_share(const RankJob& job, int rank, int ranks,
                                              const fs::path& tree_file, const ProgressFn& progress,
                                              RankStats& stats) {
    const Share share{rank, ranks};
    // An LBVH is built over the ranks; any other builder on rank 0, from every light.
    const bool gather = job_build_options(job.request).builder != BuilderKind::kLbvh;
    BakeNotes notes;
    std::optional<RayCaster> caster;
    MadeLights<SceneLight> area;
    if (job.geometry) {
        Result<RayCaster> built = RayCaster::build(*job.geometry, 1);
        if (!built) return make_error("ray caster: " + built.error());
        caster.emplace(std::move(built.value()));
        Result<MadeLights<SceneLight>> made = area_lights(job, share, gather, stats, notes);
        if (!made) return made.failure();
        area = std::move(made.value());
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
    Result<MadeLights<IndirectLight>> bounced =
        indirect_lights(job, share, caster ? &*caster : nullptr, sources, gather, progress, stats, notes);
    if (!bounced) return bounced.failure();
    caster.reset();
    notes.lights.punctual = job.lights.size();
    notes.lights.area_samples = area.index.total;
    notes.lights.environment = sky.size();
    Result<BuildResult> built = BuildResult{};
    if (!gather) {
        OwnedLights owned = owned_lights(job, share, std::move(area), sky, std::move(bounced.value()), notes);
        Result<BuildReport> report =
            build_split_lbvh(std::move(owned), job_build_options(job.request), tree_file,
                             share.root() ? progress : ProgressFn{}, stats);
        if (!report) return report.failure();
        built->report = std::move(report.value());
    } else if (share.root()) {
        built = build_on_rank_zero(job, area, sky, std::move(bounced.value()), progress, notes);
    }
    if (!built) return built.failure();
    if (!share.root()) return std::optional<BuildResult>{};
    built->report.effects = std::move(notes.effects);
    built->report.lights = notes.lights;
    if (!gather) built->report.effects.push_back(phase_census(built->report, ranks));
    built->report.warnings.insert(built->report.warnings.begin(), notes.warnings.begin(),
                                  notes.warnings.end());
    return std::optional<BuildResult>(std::move(built.value()));
}

}  // namespace lc::bake
