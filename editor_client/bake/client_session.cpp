#include "editor_client/bake/client_session.h"

#include <algorithm>

#include "protocol/channel_name.h"
#include "protocol/geometry_channel.h"

namespace lc::client {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// How the server's error code reads as the bake's outcome.
ErrorKind outcome_of(ErrorCode code) {
    switch (code) {
        case ErrorCode::kCancelled: return ErrorKind::kCancelled;
        case ErrorCode::kBusy: return ErrorKind::kBusy;
        case ErrorCode::kVersionMismatch:
        case ErrorCode::kAuthentication: return ErrorKind::kRefused;
        default: return ErrorKind::kFailed;
    }
}

}  // namespace

ClientSession::ClientSession(std::vector<SceneLight> lights, const Guid& scene_guid, ClientSessionOptions options)
    : lights_(std::move(lights)),
      scene_channel_(scene_channel_name(scene_guid)),
      geometry_channel_(options.geometry ? geometry_channel_name(scene_guid) : std::string()),
      options_(std::move(options)) {}

void ClientSession::start() {
    if (stage_ != Stage::kConnecting) return;
    stage_ = Stage::kAwaitingHelloAck;
    outbox_.push_back(HelloMsg{kProtocolVersion, "editor_client 0.1.0", options_.token});
}

std::optional<Message> ClientSession::next_message() {
    if (finished()) return std::nullopt;
    if (!outbox_.empty()) {
        Message message = std::move(outbox_.front());
        outbox_.pop_front();
        return message;
    }
    if (stage_ == Stage::kUploading) return next_upload_message();
    return std::nullopt;
}

// The scene channel (the tree lights, count-prefixed, in bounded chunks), the
// geometry channel when one is due, then BakeRequest; one message at a time,
// so a chunk exists only while it is sent.
std::optional<Message> ClientSession::next_upload_message() {
    switch (upload_step_) {
        case UploadStep::kOpen:
            if (!scene_sent_) {
                channel_id_ = kSceneChannelId;
                channel_name_ = scene_channel_;
                channel_bytes_ = encode_scene_channel(lights_);
                lights_ = {};
                upload_start_ = Clock::now();
            } else {
                channel_id_ = kGeometryChannelId;
                channel_name_ = geometry_channel_;
                channel_bytes_ = encode_geometry_channel(*options_.geometry);
                options_.geometry.reset();
            }
            upload_offset_ = 0;
            upload_step_ = channel_bytes_.empty() ? UploadStep::kClose : UploadStep::kData;
            return OpenChannelMsg{channel_id_, channel_name_, channel_bytes_.size()};
        case UploadStep::kData: {
            size_t n = std::min<uint64_t>(options_.chunk_bytes, channel_bytes_.size() - upload_offset_);
            auto begin = channel_bytes_.begin() + static_cast<ptrdiff_t>(upload_offset_);
            WriteChannelMsg write{channel_id_, upload_offset_, {begin, begin + static_cast<ptrdiff_t>(n)}};
            upload_offset_ += n;
            if (upload_offset_ == channel_bytes_.size()) upload_step_ = UploadStep::kClose;
            return write;
        }
        case UploadStep::kClose: {
            if (options_.recorder && options_.recorder->enabled()) {
                if (Status recorded = options_.recorder->record(channel_name_, channel_bytes_); !recorded) {
                    finish(make_error(recorded.error()));
                    return std::nullopt;
                }
            }
            channel_bytes_ = {};
            const bool geometry_due = !scene_sent_ && !geometry_channel_.empty();
            scene_sent_ = true;
            upload_step_ = geometry_due ? UploadStep::kOpen : UploadStep::kRequest;
            return CloseChannelMsg{channel_id_};
        }
        case UploadStep::kRequest: {
            upload_step_ = UploadStep::kDone;
            stage_ = Stage::kBaking;
            outcome_.upload_ms = ms_since(upload_start_);
            BakeRequestMsg request = options_.request;
            request.scene_channel = scene_channel_;
            request.geometry_channel = geometry_channel_;
            return request;
        }
        case UploadStep::kDone: break;
    }
    return std::nullopt;
}

void ClientSession::on_message(const Message& message) {
    // During the upload the server has nothing to say but an error, which ends the bake as it would after it.
    if (stage_ == Stage::kAwaitingHelloAck) on_hello_reply(message);
    else if (stage_ == Stage::kUploading || stage_ == Stage::kBaking) on_bake_message(message);
}

void ClientSession::on_hello_reply(const Message& message) {
    if (auto* error = std::get_if<ErrorMsg>(&message)) {
        finish(make_error("server refused the connection: " + error->text,
                          error->code == ErrorCode::kBusy ? ErrorKind::kBusy : ErrorKind::kRefused));
        return;
    }
    auto* ack = std::get_if<HelloAckMsg>(&message);
    if (!ack) {
        finish(make_error(std::string("expected HelloAck, got ") + message_name(message)));
        return;
    }
    if (ack->protocol_version != kProtocolVersion) {
        finish(make_error("protocol version mismatch: server speaks " + ack->protocol_version.to_hex() +
                              ", client speaks " + kProtocolVersion.to_hex(),
                          ErrorKind::kRefused));
        return;
    }
    stage_ = Stage::kUploading;
}

void ClientSession::on_bake_message(const Message& m) {
    if (auto* p = std::get_if<ProgressMsg>(&m)) {
        if (options_.on_progress) options_.on_progress(*p);
    } else if (auto* w = std::get_if<WarningMsg>(&m)) {
        outcome_.warnings.push_back(w->text);
        if (options_.on_warning) options_.on_warning(w->text);
    } else if (auto* e = std::get_if<ErrorMsg>(&m)) {
        finish(make_error(e->code == ErrorCode::kCancelled ? "bake cancelled" : "server: " + e->text,
                          outcome_of(e->code)));
    } else if (auto* open = std::get_if<OpenChannelMsg>(&m)) {
        auto name = ChannelName::parse(open->name);
        if (!name || name->version != kLightcutsVersionGuid || name->extension != kLightcutsExtension)
            return finish(make_error("server opened an unexpected channel '" + open->name + "' (expected version " +
                                     kLightcutsVersionGuid.to_hex() + ", extension ." + kLightcutsExtension + ")"));
        if (result_channel_id_) return finish(make_error("server opened a second result channel"));
        result_channel_id_ = open->channel_id;
        outcome_.result_channel_name = open->name;
        expected_bytes_ = open->total_bytes;
        download_start_ = Clock::now();
    } else if (auto* write = std::get_if<WriteChannelMsg>(&m)) {
        if (!result_channel_id_ || write->channel_id != *result_channel_id_)
            return finish(make_error("server wrote to channel " + std::to_string(write->channel_id) +
                                     " which is not open"));
        if (write->offset != result_bytes_.size() || result_bytes_.size() + write->data.size() > expected_bytes_)
            return finish(make_error("result channel out of order or longer than announced"));
        if (Status s = reader_.consume(write->data); !s) return finish(make_error("result channel: " + s.error()));
        result_bytes_.insert(result_bytes_.end(), write->data.begin(), write->data.end());
        if (options_.on_progress && reader_.nodes_expected() > 0) {
            float pct = 100.0f * static_cast<float>(reader_.nodes_received()) /
                        static_cast<float>(reader_.nodes_expected());
            options_.on_progress(ProgressMsg{options_.request.bake_id, "receiving", pct});
        }
    } else if (auto* close = std::get_if<CloseChannelMsg>(&m)) {
        if (!result_channel_id_ || close->channel_id != *result_channel_id_)
            return finish(make_error("server closed a channel that is not open"));
        channel_closed_ = true;
    } else if (auto* done = std::get_if<BakeDoneMsg>(&m)) {
        if (!channel_closed_) return finish(make_error("BakeDone arrived before the result channel was closed"));
        Result<LightTree> tree = reader_.finish();
        if (!tree) return finish(make_error("result channel: " + tree.error()));
        if (tree->nodes.size() != done->node_count)
            return finish(make_error("BakeDone announces " + std::to_string(done->node_count) +
                                     " nodes, channel held " + std::to_string(tree->nodes.size())));
        outcome_.tree = std::move(tree.value());
        outcome_.done = *done;
        outcome_.download_ms = ms_since(download_start_);
        if (options_.recorder && options_.recorder->enabled()) {
            Status recorded = options_.recorder->record(outcome_.result_channel_name, result_bytes_);
            if (!recorded) return finish(make_error(recorded.error()));
        }
        outcome_.result_channel = std::move(result_bytes_);
        finish(std::move(outcome_));
    } else {
        finish(make_error(std::string("unexpected message from the server: ") + message_name(m)));
    }
}

void ClientSession::cancel() {
    if (finished() || cancel_sent_) return;
    if (stage_ != Stage::kBaking) {
        finish(make_error("bake cancelled", ErrorKind::kCancelled));
        return;
    }
    cancel_sent_ = true;
    outbox_.push_back(CancelMsg{options_.request.bake_id});
}

void ClientSession::fail(Error error) {
    if (!finished()) finish(std::move(error));
}

void ClientSession::finish(Result<BakeOutcome> result) {
    stage_ = Stage::kFinished;
    outbox_.clear();
    result_.emplace(std::move(result));
}

Result<BakeOutcome> ClientSession::take_result() {
    if (!result_) return make_error("the bake has not finished");
    Result<BakeOutcome> result = std::move(*result_);
    result_.reset();
    return result;
}

}  // namespace lc::client
