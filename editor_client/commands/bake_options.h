#pragma once
// The bake flags shared by every command that can bake (bake, render, view).
#include <CLI/CLI.hpp>

#include <string>

#include "editor_client/bake/bake_client.h"
#include "editor_client/commands/environment_flags.h"
#include "lightcuts/scene.h"

namespace lc::client {

struct BakeFlags {
    std::string server;
    bool spawn_server = false;
    std::string token_file;
    bool tls = false;
    std::string tls_ca;
    // auto: optimal-pair up to kAutoBuilderLightLimit tree lights, agglomerative up to
    // kAutoLbvhLightLimit, LBVH above.
    std::string builder = "auto";
    std::string pairing = "auto";
    std::string representative = "intensity";
    uint32_t exact_limit = 0;
    uint64_t seed = 0;
    uint32_t area_lights = kDefaultAreaLights;
    std::string record_dir;
    double connect_timeout = 10.0;
    EnvironmentFlags environment;
    std::string indirect = "off";
    IndirectRequest indirect_request;
    uint32_t ranks = 0;  // 0: the server bakes in its own process
    std::vector<std::string> server_args;  // --server-arg: flags for the --spawn-server server

    // Adds --server, --spawn-server, --token-file, --tls, --tls-ca, --builder,
    // --pairing, --representative, --exact-limit, --seed, --area-lights, --ranks, --record,
    // --connect-timeout, the environment flags (environment_flags.h) and the indirect
    // light's --indirect, --bounces, --vpl-count, --patch-size and --tolerance to a subcommand.
    // `renders`: the subcommand also renders, and its --indirect takes `on` (the
    // default: bake no bounce, shade the tree's indirect lights); `off` then
    // also leaves the tree's indirect lights out of the render.
    void add_to(CLI::App& cmd, bool server_required, bool renders = false);
    // The tree's indirect lights are shaded (render --indirect anything but off).
    bool renders_indirect() const { return indirect != "off"; }
    bool has_server() const { return spawn_server || !server.empty(); }
    // Loads the environment, the flags' or else the scene's (Scene::environment),
    // if any; a subcommand ends on a bad one (command_errors.h).
    BakeClientOptions to_options(const Scene& scene) const;
    // The tree lights a bake of `scene` with these flags is expected to hold:
    // the scene's (not classic), and what the server makes: --area-lights where
    // a material emits, the environment's lights, the VPLs the server
    // reserves for --vpl-count paths (vpl_light_reservation) (radiosity patches are not counted: they depend on the
    // meshes' area).
    size_t expected_tree_lights(const Scene& scene) const;
    // The builder a bake of `scene` uses: --builder, or for auto the one its
    // expected tree size picks; `why` (if given) is set to the reason auto chose it.
    std::string resolved_builder(const Scene& scene, std::string* why = nullptr) const;
};

// Above this many tree lights, --builder auto bakes agglomeratively: the
// optimal-pair build took 30 s of a 34 s bake at 2^20 lights (docs/BENCHMARKS.md).
inline constexpr size_t kAutoBuilderLightLimit = size_t{1} << 17;
// Above this many, by LBVH: the agglomerative build took 8.9 s of an 11.2 s bake
// at 2^20 lights on an idle two-core box, the LBVH 1.4 s, for a tree about 1.25x
// the agglomerative's error at the same E (docs/BENCHMARKS.md).
inline constexpr size_t kAutoLbvhLightLimit = size_t{1} << 19;

}  // namespace lc::client
