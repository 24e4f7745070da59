#pragma once
// The bake client's side of the channel protocol as a state machine with no
// socket and no files: Hello, the scene channel, BakeRequest, then progress and
// warnings, the result channel into a ResultChannelReader, and BakeDone, an
// error or a cancel. The I/O layer (bake_client.cpp) moves the bytes: it pulls
// messages to send with next_message() and pushes what arrives into
// on_message(); what else the session decides (progress and warnings to show,
// channels to record, the result's dump to write) it emits as ClientActions
// (client_action.h) for the I/O layer to apply, so every rule here is tested
// without a socket or a file (tests/client_session_test.cpp).
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "editor_client/bake/bake_outcome.h"
#include "editor_client/bake/channel_upload.h"
#include "editor_client/bake/client_action.h"
#include "editor_client/bake/result_download.h"
#include "lightcuts/environment.h"
#include "lightcuts/guid.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"
#include "lightcuts/scene_light.h"
#include "protocol/channel_records.h"
#include "protocol/messages.h"

namespace lc::client {

struct ClientSessionOptions {
    std::string token;
    // The bake to ask for; the session names its scene channel.
    BakeRequestMsg request{.bake_id = 1};
    // Non-null: sent on the environment channel after the scene channel, and
    // named in the request (request.environment_lights is its light budget).
    std::shared_ptr<const Environment> environment;
    size_t chunk_bytes = kDefaultChunkBytes;
    // --record: every channel sent and received is emitted whole (RecordChannel).
    bool record_channels = false;
    // False: BakeOutcome::result_channel stays empty; the tree is decoded as
    // the channel streams in, and a million-light channel is 180 MB more.
    bool keep_result_channel = true;
    // False: every record and the tree's structure are validated as they
    // arrive and nothing of them is kept (BakeOutcome::tree stays empty): for
    // `bake`, which needs the tree only valid, in the dump.
    bool decode_tree = true;
    // bake -o: the result channel goes into a dump as it arrives (OpenDump,
    // AppendDump), committed at BakeDone once the tree is valid (CommitDump);
    // a failed bake discards it (DiscardDump).
    bool write_dump = false;
    // Sent on the geometry channel after the scene channel when an effect
    // needs the surfaces (surface_geometry.h); null: no geometry channel.
    std::shared_ptr<const SceneGeometry> geometry;
};

class ClientSession {
public:
    enum class Stage { kConnecting, kAwaitingHelloAck, kUploading, kBaking, kFinished };

    // `lights`: the tree lights only (classic lights stay with the client).
    ClientSession(std::vector<SceneLight> lights, const Guid& scene_guid, ClientSessionOptions options);

    // The transport is connected: Hello is due.
    void start();
    // The next message to send, or nothing when none is due until more arrives.
    std::optional<Message> next_message();
    void on_message(const Message& message);
    // The user cancelled: before BakeRequest is sent the bake ends here (the I/O
    // layer closes the connection); after it, Cancel is sent once and the
    // server's answer ends the bake.
    void cancel();
    // The transport failed or timed out; ignored once finished.
    void fail(Error error);
    // Applying one of the session's actions failed (a dump or a recording
    // could not be written): the bake fails, even one that had finished with
    // its outcome, and an open dump is discarded (take_actions).
    void fail_outputs(Error error);
    // What the I/O layer is to do, in order, since the last call: take them
    // after every call into the session (AppendDump views its message).
    ClientActions take_actions() { return std::exchange(actions_, {}); }

    Stage stage() const { return stage_; }
    bool finished() const { return stage_ == Stage::kFinished; }
    bool succeeded() const { return result_ && result_->ok(); }
    // Once finished: the outcome, moved out.
    Result<BakeOutcome> take_result();

private:
    using Clock = std::chrono::steady_clock;
    // The result's dump (bake -o): none asked, open, or its commit emitted with the outcome.
    enum class Dump { kNone, kOpen, kCommitting };

    std::optional<Message> next_upload_message();
    ChannelUpload start_upload();
    BakeRequestMsg bake_request();
    void on_hello_reply(const Message& message);
    void on_bake_message(const Message& message);
    void on_result_open(const OpenChannelMsg& open);
    void on_result_write(const WriteChannelMsg& write);
    void on_bake_done(const BakeDoneMsg& done);
    void finish(Result<BakeOutcome> result);

    static constexpr uint32_t kSceneChannelId = 1;
    static constexpr uint32_t kGeometryChannelId = 2;
    static constexpr uint32_t kEnvironmentChannelId = 3;

    std::vector<SceneLight> lights_;
    std::string scene_channel_;
    std::string environment_channel_;
    std::string geometry_channel_;  // empty: none to send
    ClientSessionOptions options_;
    Stage stage_ = Stage::kConnecting;
    std::deque<Message> outbox_;
    ClientActions actions_;
    bool cancel_sent_ = false;
    std::optional<Result<BakeOutcome>> result_;

    std::optional<ChannelUpload> upload_;  // made when the upload starts, gone once BakeRequest is sent
    Clock::time_point upload_start_;
    ResultDownload download_;
    Dump dump_ = Dump::kNone;
    BakeOutcome outcome_;
};

}  // namespace lc::client
