#include "lightmass_server/builders/tree_builder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <chrono>
#include <cmath>
#include <string>

#include "lightcuts/tree/build_tree.h"
#include "lightcuts/tree/tree_export.h"
#include "lightmass_server/builders/agglomerative_builder.h"
#include "lightmass_server/builders/build_phase_timer.h"
#include "lightmass_server/builders/cluster_attributes.h"
#include "lightmass_server/builders/lbvh_builder.h"
#include "lightmass_server/builders/optimal_pair_builder.h"

namespace lc::bake {
namespace {

constexpr uint32_t kMaxBuildLights = 1u << 24;  // arena indices stay in int32

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

Status validate_options(const BuildOptions& options) {
    switch (options.builder) {
        case BuilderKind::kOptimalPair: break;
        case BuilderKind::kAgglomerative: break;
        case BuilderKind::kLbvh: break;
        default: return make_error("unknown builder kind " + std::to_string(int(options.builder)));
    }
    switch (options.representative_rule) {
        case RepresentativeRule::kIntensity: break;
        case RepresentativeRule::kThesisFirst: break;
        default:
            return make_error("unknown representative rule " +
                              std::to_string(int(options.representative_rule)));
    }
    switch (options.pairing) {
        case PairingMode::kExact: break;
        case PairingMode::kApproximate: break;
        case PairingMode::kAuto: break;
        default: return make_error("unknown pairing mode " + std::to_string(int(options.pairing)));
    }
    return Ok{};
}

// The builders trust these; anything else would turn into NaN inside a sum.
Status check_light(const SceneLight& light, size_t i) {
    // Named only on failure: a million lights must not cost a million strings.
    const auto name = [&] { return "light " + std::to_string(i) + " (" + light.guid.to_hex() + ")"; };
    if (int(light.type) >= kLightTypeCount) {
        return make_error(name() + " has an unknown type " + std::to_string(int(light.type)));
    }
    if (!finite3(light.position) || !finite3(light.direction) || !finite3(light.color)) {
        return make_error(name() + " has a non-finite position, direction or color");
    }
    if (!std::isfinite(light.intensity) || light.intensity < 0.0f) {
        return make_error(name() + " has an invalid intensity (must be finite and >= 0)");
    }
    if (light.color.x < 0.0f || light.color.y < 0.0f || light.color.z < 0.0f) {
        return make_error(name() + " has a negative color component");
    }
    if (!std::isfinite(light.range) || light.range < 0.0f) {
        return make_error(name() + " has an invalid range (must be finite and >= 0)");
    }
    if (!std::isfinite(light.inner_cone_angle) || !std::isfinite(light.outer_cone_angle)) {
        return make_error(name() + " has non-finite spot cone angles");
    }
    if (!std::isfinite(light.source_radius) || light.source_radius < 0.0f) {
        return make_error(name() + " has an invalid source radius (must be finite and >= 0)");
    }
    if (light.patch && !light.indirect) return make_error(name() + " is a patch but not indirect");
    if (light.source_radius > 0.0f && !light.patch) {
        return make_error(name() + " has a source radius but is not a patch");
    }
    if (light.bounce != 0 && (!light.indirect || light.patch)) {
        return make_error(name() + " has a bounce but is not a VPL");
    }
    return Ok{};
}

Status validate_lights(std::span<const SceneLight> lights) {
    if (lights.size() > kMaxBuildLights) {
        return make_error("too many lights for one tree: " + std::to_string(lights.size()) +
                          " (limit " + std::to_string(kMaxBuildLights) + ")");
    }
    // The first bad light in input order, whichever thread finds which: the
    // smallest index over the chunks.
    const size_t first_bad = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, lights.size(), 1u << 14), lights.size(),
        [&](const tbb::blocked_range<size_t>& range, size_t found) {
            for (size_t i = range.begin(); i != range.end() && i < found; ++i) {
                if (!check_light(lights[i], i)) return i;
            }
            return found;
        },
        [](size_t a, size_t b) { return std::min(a, b); });
    if (first_bad == lights.size()) return Ok{};
    return check_light(lights[first_bad], first_bad);
}

std::string light_group_name(size_t group) {
    const std::string type = light_type_name(LightType(group % kLightTypeCount));
    const char* kinds[] = {"", "indirect ", "patch "};
    return kinds[group / kLightTypeCount] + type;
}

// The lights' indices by light group. Millions of lights take tens of
// milliseconds here: a cancel is asked every 65,536 of them (a small build
// reaches its first level's polls); false when it came.
bool group_leaves(std::span<const SceneLight> lights, const BakeStop* stop,
                  std::array<std::vector<uint32_t>, kLightGroupCount>& leaves_by_group) {
    StopPoll poll(stop);
    for (uint32_t i = 0; i < lights.size(); ++i) {
        if ((i & 0xFFFFu) == 0xFFFFu && poll.now()) return false;
        leaves_by_group[light_group(lights[i])].push_back(i);
    }
    return true;
}

// The per-group roots joined left to right under junction nodes: the whole tree's root.
int32_t join_under_junctions(BuildArena& arena, const std::vector<uint32_t>& roots) {
    int32_t root = roots.empty() ? kNoChild : int32_t(roots[0]);
    for (size_t i = 1; i < roots.size(); ++i) {
        const BuildNode junction = make_junction(arena, uint32_t(root), roots[i]);
        root = int32_t(arena.nodes.size());
        arena.nodes.push_back(junction);
    }
    return root;
}

double elapsed_ms(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

}  // namespace

size_t light_group(const SceneLight& light) {
    const size_t kind = light.patch ? 2 : light.indirect ? 1 : 0;
    return size_t(light.type) + kind * kLightTypeCount;
}

Result<BuildResult> build_light_tree(std::span<const SceneLight> lights,
                                     const BuildOptions& options, const ProgressFn& progress) {
    const auto start = std::chrono::steady_clock::now();
    BuildResult result;
    BuildReport& report = result.report;
    BuildPhaseTimer timer(report);
    if (Status status = validate_options(options); !status) return make_error(status.error());
    if (Status status = validate_lights(lights); !status) return make_error(status.error());
    timer.lap("validate lights");

    BuildOptions effective = options;
    // A bake request leaves the limit at 0 when the client did not choose one.
    if (effective.exact_pairing_limit == 0)
        effective.exact_pairing_limit = kDefaultExactPairingLimit;

    BuildArena arena;
    arena.lights = lights;
    arena.nodes.reserve(2 * lights.size() + kLightGroupCount);
    // The leaves' slots, never written: a leaf is made from its light when
    // read (BuildArena::node), which saves 160 bytes a light of fresh pages.
    arena.nodes.resize(lights.size());
    std::array<std::vector<uint32_t>, kLightGroupCount> leaves_by_group;
    if (!group_leaves(lights, options.stop, leaves_by_group))
        return make_error("cancelled before the build", ErrorKind::kCancelled);

    timer.lap("leaves");
    std::vector<uint32_t> roots;
    size_t lights_done = 0;
    for (size_t g = 0; g < kLightGroupCount; ++g) {
        const std::vector<uint32_t>& leaves = leaves_by_group[g];
        if (leaves.empty()) continue;
        const std::string stage = std::string(builder_name(effective.builder)) + " (" +
                                  light_group_name(g) + " lights)";
        const double weight = double(leaves.size()) / double(lights.size());
        const double offset = double(lights_done) / double(lights.size());
        const BuildProgressFn type_progress = [&](double fraction) {
            return !progress || progress(stage, 100.0 * (offset + weight * fraction));
        };

        Result<int32_t> root = make_error("unknown builder");
        switch (effective.builder) {
            case BuilderKind::kOptimalPair:
                root = build_optimal_pair_tree(arena, leaves, effective, type_progress, report);
                break;
            case BuilderKind::kAgglomerative:
                root = build_agglomerative_tree(arena, leaves, effective, type_progress, report);
                break;
            case BuilderKind::kLbvh:
                root = build_lbvh_tree(arena, leaves, effective, type_progress, report);
                break;
        }
        if (!root) return root.failure();
        timer.skip();  // each builder times its own steps
        roots.push_back(uint32_t(*root));
        lights_done += leaves.size();
    }

    // One tree per light group, joined under junction nodes (the paper's
    // "conceptually a single larger tree").
    const int32_t root = join_under_junctions(arena, roots);

    // Converting 10^6 nodes is memory-bound: two threads overlap their misses.
    const ParallelRanges tbb_ranges = [](size_t count, const std::function<void(size_t, size_t)>& body) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 1u << 14),
                          [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
    };
    timer.lap("join light types");
    ExportedTree exported = export_light_tree(arena, root, tbb_ranges);
    timer.lap("export");
    result.tree = std::move(exported.tree);
    report.depth = exported.depth;
    report.build_ms = elapsed_ms(start);
    if (progress && !progress("done", 100.0))
        return make_error("cancelled after the build", ErrorKind::kCancelled);
    return result;
}

}  // namespace lc::bake
