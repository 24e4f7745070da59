#pragma once
// The bake client's side of the channel protocol as a state machine with no
// socket: Hello, the scene channel, BakeRequest, then progress and warnings,
// the result channel into a ResultChannelReader, and BakeDone, an error or a
// cancel. The I/O layer (bake_client.cpp) moves the bytes: it pulls messages
// to send with next_message() and pushes what arrives into on_message(), so
// every rule here is tested without a socket (tests/client_session_test.cpp).
#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "editor_client/bake/bake_client.h"
#include "lightcuts/environment.h"
#include "lightcuts/guid.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"
#include "lightcuts/scene_light.h"
#include "protocol/channel_recorder.h"
#include "protocol/channel_records.h"
#include "protocol/dump.h"
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
    std::function<void(const ProgressMsg&)> on_progress;
    std::function<void(const std::string&)> on_warning;
    const ChannelRecorder* recorder = nullptr;  // null or disabled: nothing is recorded
    // False: BakeOutcome::result_channel stays empty; the tree is decoded as
    // the channel streams in, and a million-light channel is 180 MB more.
    bool keep_result_channel = true;
    // False: every record and the tree's structure are validated as they
    // arrive and nothing of them is kept (BakeOutcome::tree stays empty): for
    // `bake`, which needs the tree only valid, in the dump.
    bool decode_tree = true;
    // Non-empty: the result channel goes into this dump as it arrives (a
    // DumpWriter), committed at BakeDone once the tree is valid; a failed bake
    // leaves no dump and any earlier one at that path untouched.
    std::filesystem::path result_dump;
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

    Stage stage() const { return stage_; }
    bool finished() const { return stage_ == Stage::kFinished; }
    bool succeeded() const { return result_ && result_->ok(); }
    // Once finished: the outcome, moved out.
    Result<BakeOutcome> take_result();

private:
    using Clock = std::chrono::steady_clock;
    enum class UploadStep { kOpen, kData, kClose, kRequest, kDone };

    std::optional<Message> next_upload_message();
    void on_hello_reply(const Message& message);
    void on_bake_message(const Message& message);
    void finish(Result<BakeOutcome> result);

    struct UploadChannel {
        uint32_t id = 0;
        std::string name;
        std::vector<uint8_t> bytes;
    };

    std::vector<SceneLight> lights_;
    std::string scene_channel_;
    std::string environment_channel_;
    std::string geometry_channel_;  // empty: none to send
    ClientSessionOptions options_;
    Stage stage_ = Stage::kConnecting;
    std::deque<Message> outbox_;
    bool cancel_sent_ = false;
    std::optional<Result<BakeOutcome>> result_;

    // Upload.
    static constexpr uint32_t kSceneChannelId = 1;
    static constexpr uint32_t kGeometryChannelId = 2;
    static constexpr uint32_t kEnvironmentChannelId = 3;
    UploadStep upload_step_ = UploadStep::kOpen;
    std::vector<UploadChannel> uploads_;  // the scene channel, then the geometry's and the environment's when due
    size_t upload_index_ = 0;
    uint64_t upload_offset_ = 0;
    Clock::time_point upload_start_;

    // Result channel.
    BakeOutcome outcome_;
    ResultChannelReader reader_;
    std::vector<uint8_t> result_bytes_;  // kept for the outcome or the recorder
    std::optional<DumpWriter> result_dump_;
    uint64_t result_received_ = 0;
    std::optional<uint32_t> result_channel_id_;
    uint64_t expected_bytes_ = 0;
    bool channel_closed_ = false;
    Clock::time_point download_start_;
};

}  // namespace lc::client
