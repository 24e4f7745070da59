#pragma once
// Bakes a scene on a lightmass_server (remote, or spawned locally): sends the
// scene channel, follows progress, receives the result channel and decodes it.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "editor_client/bake/bake_outcome.h"
#include "lightcuts/environment.h"
#include "lightcuts/guid.h"
#include "lightcuts/tree/light_tree.h"
#include "lightcuts/scene_geometry.h"
#include "protocol/messages.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"

namespace lc::client {

// Lets another thread (the editor's Cancel button) wake a running bake's I/O at
// once to look at BakeClientOptions::cancel; without it the bake looks at the
// flag with each message from the server.
class BakeWaker {
public:
    // Thread-safe; nothing happens while no bake is attached.
    void wake();
    // bake_lights attaches its I/O for the length of the bake.
    void attach(std::function<void()> wake);
    void detach();

private:
    std::mutex mutex_;
    std::function<void()> wake_;
};

struct BakeClientOptions {
    std::string server;            // "HOST:PORT"; ignored when spawn_server
    bool spawn_server = false;     // start build/bin/lightmass_server on loopback for this bake
    // The spawned server's own flags (--server-arg), e.g. --mpi-oversubscribe=on.
    std::vector<std::string> spawned_server_args;
    std::filesystem::path token_file;
    // TLS to a server started with --tls-cert: the certificate must verify
    // against tls_ca_file (PEM: a CA, or the server's self-signed certificate),
    // or the system's trust store when it is empty, and name the host of `server`.
    bool tls = false;
    std::filesystem::path tls_ca_file;
    std::filesystem::path record_dir;  // when set, every channel's bytes are dumped there
    bool keep_result_channel = true;   // false: BakeOutcome::result_channel stays empty
    // False: the tree is validated as it arrives and not kept (BakeOutcome::tree
    // stays empty), for a client that needs it only in the dump.
    bool decode_tree = true;
    // Non-empty: the result channel is written to this dump (bake -o) as it
    // arrives, and the dump committed once the whole tree is valid.
    std::filesystem::path result_dump;
    BuilderKind builder = BuilderKind::kOptimalPair;
    RepresentativeRule representative_rule = RepresentativeRule::kIntensity;
    PairingMode pairing = PairingMode::kAuto;
    uint32_t exact_pairing_limit = 0;  // 0: server default
    uint64_t seed = 0;
    // Non-null: sent on the environment channel and sampled into
    // environment_lights directional lights (0: the server's default).
    std::shared_ptr<const Environment> environment;
    uint32_t environment_lights = 0;
    // The scene's surfaces, sent on the geometry channel; null: none (no
    // effect needs them, see surface_geometry.h's geometry_the_bake_needs).
    std::shared_ptr<const SceneGeometry> geometry;
    uint32_t area_lights = 0;  // area-light sample budget; 0: the server's default
    IndirectRequest indirect;
    uint32_t ranks = 0;  // 0: the server bakes in its process; N: over N MPI ranks
    double timeout_seconds = 600.0;    // whole bake, transfer included
    // From connecting until HelloAck (TCP, TLS handshake, Hello): a server that
    // accepts and never answers is given up on after this long.
    double connect_timeout_seconds = 10.0;
    std::function<void(const ProgressMsg&)> on_progress;
    std::function<void(const std::string&)> on_warning;
    const std::atomic<bool>* cancel = nullptr;  // set to true to cancel the bake
    BakeWaker* waker = nullptr;                 // wake() after setting `cancel` from another thread
};

// Lights marked classic are not sent: they stay with the client. A failure's
// kind says whether the bake was cancelled, the server busy or the connection
// refused (version, token).
Result<BakeOutcome> bake_lights(std::span<const SceneLight> lights, const Guid& scene_guid,
                                const BakeClientOptions& options);

}  // namespace lc::client
