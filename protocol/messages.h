#pragma once
// Our own view of the wire messages. Only protocol/codec.cpp sees the
// FlatBuffers-generated code; everything else uses these types.
#include <cstdint>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "lightcuts/guid.h"

namespace lc {

// The version of the message set in lightcuts.fbs. Bump on any incompatible change.
// 1.1: StatusRequest and StatusReply, BakeDone.lights.
inline constexpr Guid kProtocolVersion{0x4C435031u, 0x50726F74u, 0x6F636F6Cu, 0x00010001u};

enum class BuilderKind : uint8_t { kOptimalPair = 0, kAgglomerative = 1, kLbvh = 2 };
enum class RepresentativeRule : uint8_t { kIntensity = 0, kThesisFirst = 1 };
enum class PairingMode : uint8_t { kExact = 0, kApproximate = 1, kAuto = 2 };
enum class IndirectMethod : uint8_t { kOff = 0, kVpl = 1, kRadiosity = 2 };

// The bounced light a bake adds to the tree, and its solver's settings.
struct IndirectRequest {
    IndirectMethod method = IndirectMethod::kOff;
    // vpl: a cap on each path's bounces; the default, every bounce a light
    // can record (kMaxBakeBounces): Russian roulette ends the paths.
    uint32_t bounces = 65535;
    uint64_t vpl_count = 100000;
    float patch_size = 0.25f;
    float tolerance = 0.01f;
};

const char* builder_name(BuilderKind kind);
const char* representative_rule_name(RepresentativeRule rule);
const char* pairing_mode_name(PairingMode mode);
const char* indirect_method_name(IndirectMethod method);

enum class ErrorCode : uint32_t {
    kUnknown = 0,
    kVersionMismatch = 1,
    kAuthentication = 2,
    kMalformedFrame = 3,
    kInvalidScene = 4,
    kUnknownChannel = 5,
    kBakeFailed = 6,
    kCancelled = 7,
    kTooLarge = 8,
    kBusy = 9,
};

struct HelloMsg {
    Guid protocol_version;
    std::string peer_name;
    std::string token;
};
struct HelloAckMsg {
    Guid protocol_version;
    std::string peer_name;
};
struct OpenChannelMsg {
    uint32_t channel_id = 0;
    std::string name;
    uint64_t total_bytes = 0;
};
struct WriteChannelMsg {
    uint32_t channel_id = 0;
    uint64_t offset = 0;
    std::vector<uint8_t> data;  // the bytes, owned: what a sender builds, what decode_message copies out
    // decode_message_in_frame leaves `data` empty and points here into the
    // frame instead: the message is handled before its frame goes.
    std::span<const uint8_t> in_frame;

    std::span<const uint8_t> bytes() const {
        return in_frame.empty() ? std::span<const uint8_t>(data) : in_frame;
    }
};
struct CloseChannelMsg {
    uint32_t channel_id = 0;
};
// BakeRequest.area_lights: the oriented point lights the server samples from
// emissive triangles (0 on the wire: the default).
inline constexpr uint32_t kDefaultAreaLights = 4096;
inline constexpr uint32_t kMaxAreaLights = 1u << 22;  // 4,194,304

struct BakeRequestMsg {
    uint32_t bake_id = 0;
    std::string scene_channel;
    BuilderKind builder = BuilderKind::kOptimalPair;
    uint64_t seed = 0;
    RepresentativeRule representative_rule = RepresentativeRule::kIntensity;
    PairingMode pairing = PairingMode::kAuto;
    uint32_t exact_pairing_limit = 0;
    std::string environment_channel;  // empty: the scene has no environment
    uint32_t environment_lights = 0;  // 0: server default
    // Empty: no geometry channel (nothing in the scene needs the surfaces).
    std::string geometry_channel;
    uint32_t area_lights = 0;  // the area-light sample budget; 0: the server's default
    IndirectRequest indirect;
    uint32_t ranks = 0;  // 0: in the server's process; N: one bake over N MPI ranks
};
struct ProgressMsg {
    uint32_t bake_id = 0;
    std::string stage;
    float percent = 0.0f;
};
struct WarningMsg {
    uint32_t bake_id = 0;
    std::string text;
};
struct ErrorMsg {
    uint32_t bake_id = 0;
    ErrorCode code = ErrorCode::kUnknown;
    std::string text;
};
struct CancelMsg {
    uint32_t bake_id = 0;
};
// The tree's lights by where they came from: the scene's punctual lights (the
// classic ones stay with the client), the emissive triangles' samples, the
// environment's lights, and the bounced light (VPLs or radiosity patches).
struct TreeLightCounts {
    uint64_t punctual = 0;
    uint64_t area_samples = 0;
    uint64_t environment = 0;
    uint64_t vpls = 0;
    uint64_t patches = 0;

    uint64_t total() const { return punctual + area_samples + environment + vpls + patches; }
    // `count` bounced lights of the kind `method` makes.
    void add_bounced(IndirectMethod method, uint64_t count) {
        (method == IndirectMethod::kRadiosity ? patches : vpls) += count;
    }
    bool operator==(const TreeLightCounts&) const = default;
};

struct BakeDoneMsg {
    uint32_t bake_id = 0;
    std::string result_channel;
    uint32_t node_count = 0;
    uint32_t leaf_count = 0;
    double build_ms = 0.0;
    double pairing_cost = 0.0;
    double pairing_lower_bound = 0.0;
    bool exact = true;
    // The bake's census, one line per effect: simulated (with counts) or skipped, and why.
    std::vector<std::string> effects;
    TreeLightCounts lights;  // all zero from a server that does not count them
};

// How the server is: asked after Hello (so a server with a token answers only
// clients that presented it), answered with StatusReply.
struct StatusRequestMsg {
    uint32_t request_id = 0;
};
// One bake the server holds: "queued" (admitted, waiting for a worker),
// "running" (with its latest progress) or "streaming" (its tree on the way out).
struct BakeStatusEntry {
    uint64_t connection = 0;
    uint32_t bake_id = 0;
    std::string state;
    std::string stage;
    float percent = 0.0f;
    uint32_t ranks = 0;
};
struct StatusReplyMsg {
    uint32_t request_id = 0;
    std::string version;  // lightmass_server's --version
    double uptime_seconds = 0.0;
    std::vector<BakeStatusEntry> bakes;
    uint64_t memory_budget_bytes = 0;  // --memory-budget-mb
    uint64_t memory_held_bytes = 0;    // channels, stored scenes and bakes' estimated peaks now
    uint32_t connections = 0;
    uint32_t max_connections = 0;
    uint32_t max_concurrent_bakes = 0;  // big bakes at once (the lanes' width)
    uint32_t max_bake_seconds = 0;
    std::string mpi_launcher;
    uint32_t mpi_max_ranks = 0;  // 0: no bakes over ranks
};

using Message = std::variant<HelloMsg, HelloAckMsg, OpenChannelMsg, WriteChannelMsg,
                             CloseChannelMsg, BakeRequestMsg, ProgressMsg, WarningMsg, ErrorMsg,
                             CancelMsg, BakeDoneMsg, StatusRequestMsg, StatusReplyMsg>;

const char* message_name(const Message& message);

}  // namespace lc
