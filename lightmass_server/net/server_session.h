#pragma once
// The server's side of the channel protocol as a state machine with no socket:
// decoded messages, and what the bake workers report, go in; messages to send
// and actions for the I/O layer come out, in order. The connection (Asio)
// only moves bytes and carries the actions out, so every protocol rule here
// is tested without a socket (tests/server_session_test.cpp).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "lightcuts/environment.h"
#include "lightcuts/tree/light_tree.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/bake/bake_pipeline.h"
#include "lightmass_server/net/incoming_channel.h"
#include "lightmass_server/net/memory_budget.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_records.h"
#include "protocol/environment_records.h"
#include "protocol/geometry_channel.h"
#include "protocol/messages.h"

namespace lc::bake {

struct ServerSessionOptions {
    uint64_t connection_id = 0;        // for the log
    std::optional<std::string> token;  // when set, Hello must carry it
    bool record_channels = false;      // emit RecordChannel for every channel received or sent
    // Non-empty: the server is full; Hello is answered kBusy with this text and the connection closes.
    std::string busy_reason;
    // Shared by every connection; null: unlimited. Holds the channels and
    // each bake's estimated peak (bake_footprint.h).
    MemoryBudget* memory_budget = nullptr;
    // Announced bytes of this connection's open channels together; 0: no cap
    // beyond the budget. Keeps one connection from holding the whole budget.
    uint64_t max_connection_channel_bytes = 0;
    // Answers a StatusRequest (the server's state over every connection); null: the version alone.
    std::function<StatusReplyMsg()> status;
};

// Send this message now (after those already queued).
struct SendMessage {
    Message message;
};
// Build this tree on the worker pool; report back with on_bake_progress and on_bake_finished.
struct StartBake {
    uint32_t bake_id = 0;
    BakeInputs inputs;
    // Small enough for the small-bake lane (bake_lanes.h), so it does not wait behind big ones.
    bool small = false;
};
// Stop the running build (it reports back with a cancelled error).
struct CancelBake {
    uint32_t bake_id = 0;
};
// Stream this tree as the result channel, then BakeDone; call on_result_delivered when sent.
struct StreamResult {
    std::shared_ptr<const LightTree> tree;
    std::shared_ptr<const ResultChannelFile> file;  // instead of `tree`: a bake over MPI ranks
    uint32_t channel_id = 0;
    BakeDoneMsg done;
};
// Stop streaming the result: the client discards the partial channel.
struct StopStream {};
// Write this channel's bytes as a dump (--record).
struct RecordChannel {
    std::string name;
    std::vector<uint8_t> bytes;
};
// Send what is queued, then close: the peer broke the protocol.
struct CloseAfterFlush {
    std::string reason;
};

using ServerAction =
    std::variant<SendMessage, StartBake, CancelBake, StreamResult, StopStream, RecordChannel, CloseAfterFlush>;
using ServerActions = std::vector<ServerAction>;

inline constexpr size_t kMaxOpenChannels = 4;
inline constexpr size_t kMaxStoredScenes = 4;

class ServerSession {
public:
    explicit ServerSession(ServerSessionOptions options);

    ServerActions on_message(Message message);
    // A frame that did not decode, or a header the frame decoder refused.
    ServerActions on_malformed_frame(const std::string& error);
    ServerActions on_bad_frame_header(const std::string& error);
    // From the worker running `bake_id` (stale reports are dropped).
    ServerActions on_bake_progress(const ProgressMsg& progress);
    ServerActions on_bake_finished(uint32_t bake_id, Result<BuildResult> result);
    // The I/O layer sent the whole result stream of the running bake.
    void on_result_delivered();
    // The connection is closing (peer gone, protocol broken, server stopping):
    // a running build is cancelled; nothing more is answered.
    ServerActions on_closing();
    // The server stops (SIGTERM) or restarts (SIGHUP): a bake running or streaming
    // is told it was stopped and why, then the connection closes after a flush.
    ServerActions on_server_stopping(const std::string& reason);

    bool greeted() const { return greeted_; }
    // No bake running or streaming and no channel half-received: the idle timeout applies.
    bool idle() const { return !bake_ && incoming_.empty(); }
    // A channel is open and not yet complete: the peer must keep sending (the read deadline applies).
    bool receiving_channel() const { return !incoming_.empty(); }
    bool bake_running() const { return bake_.has_value(); }
    bool streaming() const { return bake_ && bake_->streaming; }
    // This connection's bake for a StatusReply: queued until its first progress, then running, then streaming.
    std::optional<BakeStatusEntry> bake_status() const;

private:
    struct StoredScene {
        std::vector<SceneLight> lights;
        BudgetReservation reservation;
    };
    struct StoredEnvironment {
        std::shared_ptr<const Environment> environment;
        BudgetReservation reservation;
    };
    struct StoredGeometry {
        std::shared_ptr<const SceneGeometry> geometry;
        BudgetReservation reservation;
    };
    struct ActiveBake {
        uint32_t bake_id = 0;
        bool cancel_requested = false;
        bool streaming = false;
        BudgetReservation reservation;  // the bake's estimated peak, until it is delivered or dropped
        uint32_t ranks = 0;
        ProgressMsg latest;  // empty stage: no worker has reported yet (queued)
    };

    // Each returns false when the peer broke the protocol and the connection must close.
    bool on_hello(const HelloMsg& hello);
    bool on_open_channel(const OpenChannelMsg& open);
    bool on_write_channel(WriteChannelMsg& write);
    bool on_close_channel(const CloseChannelMsg& close);
    // A complete channel's contents, kept for bakes (the oldest of its kind makes room).
    void store_scene(IncomingChannel& channel);
    void store_environment(IncomingChannel& channel);
    void store_geometry(IncomingChannel& channel);
    // The stored channel a bake request names; null: refused, the error sent.
    template <typename Stored>
    const Stored* find_stored(const std::map<std::string, Stored>& stored, const std::string& name,
                              ChannelKind kind, uint32_t bake_id);
    bool on_bake_request(const BakeRequestMsg& request);
    // The request's settings against the protocol's limits and its stored
    // channels; false: refused, the error sent.
    bool check_bake_request(const BakeRequestMsg& request);
    // The inputs' estimated peak against the budget; false: refused (busy or too large), the error sent.
    bool reserve_bake(uint32_t bake_id, StartBake& start, BudgetReservation& reservation);
    uint64_t open_channel_bytes() const;
    // What this connection's stored scenes, environments and geometries hold against the budget.
    uint64_t stored_channel_bytes() const;
    void on_cancel(const CancelMsg& cancel);
    void on_status_request(const StatusRequestMsg& request);

    void send(Message message);
    void send_error(uint32_t bake_id, ErrorCode code, const std::string& text);
    // --record: the result channel's bytes, from the tree or the file that holds them.
    void record_result(const std::string& name, const std::shared_ptr<const LightTree>& tree,
                       const std::shared_ptr<const ResultChannelFile>& file);
    ServerActions take_actions();
    // After the error explaining why: cancel a running build, then close once it is sent.
    void close_after_flush(std::string reason);

    ServerSessionOptions options_;
    ServerActions actions_;
    bool greeted_ = false;
    bool closing_ = false;
    std::map<uint32_t, IncomingChannel> incoming_;
    std::set<uint32_t> refused_;  // channels already refused with an error: their writes are dropped
    std::map<std::string, StoredScene> scenes_;
    std::map<std::string, StoredEnvironment> environments_;
    std::map<std::string, StoredGeometry> geometries_;
    std::optional<ActiveBake> bake_;
    uint32_t next_channel_id_ = 1u << 31;  // server-opened channels use the upper half
};

}  // namespace lc::bake
