#include "editor_client/commands/bake_options.h"

#include <algorithm>
#include <glm/glm.hpp>
#include <map>

#include "editor_client/commands/command_errors.h"
#include "lightcuts/material_model.h"
#include "protocol/bake_limits.h"

namespace lc::client {

void BakeFlags::add_to(CLI::App& cmd, bool server_required, bool renders) {
    auto* server_opt = cmd.add_option("--server", server, "Bake on the server at HOST:PORT");
    auto* spawn_opt = cmd.add_flag("--spawn-server", spawn_server, "Start a local lightmass_server for this bake");
    server_opt->excludes(spawn_opt);
    if (server_required) {
        auto* group = cmd.add_option_group("server", "where to bake");
        group->add_option(server_opt);
        group->add_option(spawn_opt);
        group->require_option(1);
    }
    cmd.add_option("--token-file", token_file, "Token for a server that requires one");
    auto* tls_opt =
        cmd.add_flag("--tls", tls, "Connect to --server over TLS (a server started with --tls-cert)");
    auto* ca_opt = cmd.add_option("--tls-ca", tls_ca,
                                  "PEM CA (or the server's self-signed certificate) to verify the server "
                                  "against; implies --tls (default: the system's trusted CAs)");
    tls_opt->excludes(spawn_opt);
    ca_opt->excludes(spawn_opt);
    cmd.add_option("--builder", builder,
                   "Tree builder; auto: optimal-pair up to 131,072 lights, agglomerative up to "
                   "524,288, LBVH above")
        ->check(CLI::IsMember({"auto", "optimal-pair", "agglomerative", "lbvh"}))
        ->capture_default_str();
    cmd.add_option("--pairing", pairing, "optimal-pair pairing: exact, approximate, or auto (exact up to --exact-limit)")
        ->check(CLI::IsMember({"auto", "exact", "approximate"}))
        ->capture_default_str();
    cmd.add_option("--representative", representative,
                   "Cluster representative: intensity (the paper) or thesis-first (the thesis's Figure 9.1)")
        ->check(CLI::IsMember({"intensity", "thesis-first"}))
        ->capture_default_str();
    cmd.add_option("--exact-limit", exact_limit, "Level size above which auto pairing is approximate (0: server default)");
    cmd.add_option("--seed", seed, "Seed for representative choice")->capture_default_str();
    cmd.add_option("--area-lights", area_lights,
                   "Oriented point lights sampled from the emissive triangles, shared by their power")
        ->capture_default_str()
        ->check(CLI::Range(1u, kMaxAreaLights));
    cmd.add_option("--ranks", ranks,
                   "Bake over N MPI ranks the server launches (0: in the server's process; "
                   "the server's --mpi-max-ranks bounds N)")
        ->capture_default_str();
    cmd.add_option("--server-arg", server_args,
                   "A flag for the server --spawn-server starts (repeat), e.g. --server-arg=--mpi-oversubscribe=on "
                   "or --server-arg=--mpi-hostfile=FILE (lightmass_server --help lists them)")
        ->needs(spawn_opt)
        ->allow_extra_args(false);
    cmd.add_option("--record", record_dir, "Write every channel sent and received as a dump file here");
    cmd.add_option("--connect-timeout", connect_timeout, "Seconds to connect, finish TLS and get HelloAck")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    environment.add_to(cmd);
    if (renders) {
        indirect = "on";
        cmd.add_option("--indirect", indirect,
                       "Bounced light: on (the tree's indirect lights, clamped; a bake adds none), off "
                       "(direct light only: none baked, the tree's left out), or baked and shown: vpl "
                       "(instant radiosity) or radiosity (patches)")
            ->check(CLI::IsMember({"on", "off", "vpl", "radiosity"}))
            ->capture_default_str();
    } else {
        cmd.add_option("--indirect", indirect,
                       "Bounced light baked into the tree: off, vpl (instant radiosity) or radiosity (patches)")
            ->check(CLI::IsMember({"off", "vpl", "radiosity"}))
            ->capture_default_str();
    }
    cmd.add_option("--bounces", indirect_request.bounces, "vpl: a cap on the diffuse bounces that leave a light (default: all, until Russian roulette ends "
                   "each path)")
        ->capture_default_str()
        ->check(CLI::Range(1u, kMaxBakeBounces));
    cmd.add_option("--vpl-count", indirect_request.vpl_count,
                   "vpl: light paths traced (each leaves up to --bounces lights)")
        ->capture_default_str()
        ->check(CLI::Range(uint64_t{1}, kMaxVplPaths));
    cmd.add_option("--patch-size", indirect_request.patch_size, "radiosity: target patch edge, scene units")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd.add_option("--tolerance", indirect_request.tolerance,
                   "radiosity: stop when this fraction of the power is left unshot")
        ->capture_default_str()
        ->check(CLI::Range(0.0f, 0.999f));
}

BakeClientOptions BakeFlags::to_options(const Scene& scene) const {
    static const std::map<std::string, BuilderKind> builders = {
        {"optimal-pair", BuilderKind::kOptimalPair}, {"agglomerative", BuilderKind::kAgglomerative}, {"lbvh", BuilderKind::kLbvh}};
    static const std::map<std::string, PairingMode> pairings = {
        {"auto", PairingMode::kAuto}, {"exact", PairingMode::kExact}, {"approximate", PairingMode::kApproximate}};
    BakeClientOptions options;
    options.server = server;
    options.spawn_server = spawn_server;
    options.spawned_server_args = server_args;
    options.token_file = token_file;
    options.tls = tls || !tls_ca.empty();
    options.tls_ca_file = tls_ca;
    options.record_dir = record_dir;
    options.builder = builders.at(resolved_builder(scene));
    options.ranks = ranks;
    options.pairing = pairings.at(pairing);
    options.representative_rule =
        representative == "thesis-first" ? RepresentativeRule::kThesisFirst : RepresentativeRule::kIntensity;
    options.exact_pairing_limit = exact_limit;
    options.seed = seed;
    options.area_lights = area_lights;
    options.connect_timeout_seconds = connect_timeout;
    options.environment = or_fail(environment.load(scene.environment));
    options.environment_lights = environment.lights.value_or(0);
    static const std::map<std::string, IndirectMethod> methods = {
        {"off", IndirectMethod::kOff}, {"on", IndirectMethod::kOff}, {"vpl", IndirectMethod::kVpl},
        {"radiosity", IndirectMethod::kRadiosity}};
    options.indirect = indirect_request;
    options.indirect.method = methods.at(indirect);
    return options;
}

// Whether some material emits: the server then samples the emissive
// triangles into --area-lights lights. (A material no drawn triangle uses
// still counts: the estimate errs by area_lights at most.)
// The largest albedo channel a bounce can meet (a texture only darkens its factor).
static double largest_bounce_albedo(const Scene& scene) {
    double largest = 0.0;
    for (const Material& m : scene.materials) {
        const glm::dvec3 a = shading::bounce_albedo(glm::clamp(glm::dvec3(m.base_color_factor), 0.0, 1.0),
                                                     double(m.metallic), double(m.roughness));
        largest = std::max({largest, a.x, a.y, a.z});
    }
    return scene.materials.empty() ? 1.0 : largest;
}

static bool some_material_emits(const Scene& scene) {
    for (const Material& m : scene.materials)
        if (glm::any(glm::greaterThan(m.emissive_factor, glm::vec3(0.0f)))) return true;
    return false;
}

size_t BakeFlags::expected_tree_lights(const Scene& scene) const {
    size_t lights = 0;
    for (const SceneLight& light : scene.lights) lights += light.classic ? 0 : 1;
    if (some_material_emits(scene)) lights += area_lights;
    if (environment.requested() || scene.environment)
        lights += environment.lights.value_or(kDefaultEnvironmentLights);
    if (indirect == "vpl" && indirect_request.bounces > 0) {
        // What the server reserves: the roulette's path length at the
        // brightest material, at most one light per bounce.
        lights += size_t(
            vpl_light_reservation(indirect_request.vpl_count, indirect_request.bounces, largest_bounce_albedo(scene)));
    }
    return lights;
}

std::string BakeFlags::resolved_builder(const Scene& scene, std::string* why) const {
    if (builder != "auto") return builder;
    const size_t tree_lights = expected_tree_lights(scene);
    const bool large = tree_lights > kAutoBuilderLightLimit;
    const bool huge = tree_lights > kAutoLbvhLightLimit;
    if (why) {
        const size_t limit = huge ? kAutoLbvhLightLimit : kAutoBuilderLightLimit;
        *why = "auto: " + std::to_string(tree_lights) + (large ? " lights > " : " lights <= ") +
               std::to_string(limit);
    }
    return huge ? "lbvh" : large ? "agglomerative" : "optimal-pair";
}

}  // namespace lc::client
