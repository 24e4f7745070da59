#include "editor_client/bake/client_session.h"

#include <algorithm>

#include "lightcuts/version.h"
#include "protocol/channel_name.h"
#include "protocol/environment_records.h"
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

ClientSession::ClientSession(std::vector<SceneLight> lights, const Guid& scene_guid,
                             ClientSessionOptions options)
    : lights_(std::move(lights)),
      scene_channel_(scene_channel_name(scene_guid)),
      environment_channel_(environment_channel_name(scene_guid)),
      geometry_channel_(options.geometry ? geometry_channel_name(scene_guid) : std::string()),
      options_(std::move(options)),
      reader_(options_.decode_tree ? TreeImport::kNodes : TreeImport::kValidateOnly) {}

void ClientSession::start() {
    if (stage_ != Stage::kConnecting) return;
    stage_ = Stage::kAwaitingHelloAck;
    outbox_.push_back(HelloMsg{kProtocolVersion, std::string("editor_client ") + kVersion, options_.token});
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
// geometry channel when an effect needs the surfaces, the environment channel
// when the scene has one, then BakeRequest; one message at a time.
std::optional<Message> ClientSession::next_upload_message() {
    switch (upload_step_) {
        case UploadStep::kOpen: {
            if (uploads_.empty()) {
                upload_start_ = Clock::now();
                uploads_.push_back({kSceneChannelId, scene_channel_, encode_scene_channel(lights_)});
                // A new vector, not `= {}`: that clears and keeps the million lights' capacity.
                lights_ = std::vector<SceneLight>();
                if (options_.geometry) {
                    uploads_.push_back({kGeometryChannelId, geometry_channel_,
                                        encode_geometry_channel(*options_.geometry)});
                    options_.geometry.reset();
                }
                if (options_.environment)
                    uploads_.push_back({kEnvironmentChannelId, environment_channel_,
                                        encode_environment_channel(*options_.environment)});
            }
            const UploadChannel& channel = uploads_[upload_index_];
            upload_offset_ = 0;
            upload_step_ = channel.bytes.empty() ? UploadStep::kClose : UploadStep::kData;
            return OpenChannelMsg{channel.id, channel.name, channel.bytes.size()};
        }
        case UploadStep::kData: {
            const UploadChannel& channel = uploads_[upload_index_];
            size_t n = std::min<uint64_t>(options_.chunk_bytes, channel.bytes.size() - upload_offset_);
            auto begin = channel.bytes.begin() + static_cast<ptrdiff_t>(upload_offset_);
            WriteChannelMsg write{channel.id, upload_offset_, {begin, begin + static_cast<ptrdiff_t>(n)}};
            upload_offset_ += n;
            if (upload_offset_ == channel.bytes.size()) upload_step_ = UploadStep::kClose;
            return write;
        }
        case UploadStep::kClose: {
            const uint32_t id = uploads_[upload_index_].id;
            ++upload_index_;
            upload_step_ = upload_index_ < uploads_.size() ? UploadStep::kOpen : UploadStep::kRequest;
            return CloseChannelMsg{id};
        }
        case UploadStep::kRequest: {
            // Recorded before BakeRequest is sent: a recording that fails ends the bake first.
            if (options_.record_channels) {
                for (UploadChannel& channel : uploads_)
                    actions_.push_back(client_action::RecordChannel{channel.name, std::move(channel.bytes)});
            }
            uploads_ = std::vector<UploadChannel>();
            upload_step_ = UploadStep::kDone;
            stage_ = Stage::kBaking;
            outcome_.upload_ms = ms_since(upload_start_);
            BakeRequestMsg request = options_.request;
            request.scene_channel = scene_channel_;
            request.environment_channel = options_.environment ? environment_channel_ : std::string();
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
        actions_.push_back(client_action::ReportProgress{*p});
    } else if (auto* w = std::get_if<WarningMsg>(&m)) {
        outcome_.warnings.push_back(w->text);
        actions_.push_back(client_action::ReportWarning{w->text});
    } else if (auto* e = std::get_if<ErrorMsg>(&m)) {
        finish(make_error(e->code == ErrorCode::kCancelled ? "bake cancelled" : "server: " + e->text,
                          outcome_of(e->code)));
    } else if (auto* open = std::get_if<OpenChannelMsg>(&m)) {
        on_result_open(*open);
    } else if (auto* write = std::get_if<WriteChannelMsg>(&m)) {
        on_result_write(*write);
    } else if (auto* close = std::get_if<CloseChannelMsg>(&m)) {
        if (!result_channel_id_ || close->channel_id != *result_channel_id_)
            return finish(make_error("server closed a channel that is not open"));
        channel_closed_ = true;
    } else if (auto* done = std::get_if<BakeDoneMsg>(&m)) {
        on_bake_done(*done);
    } else {
        finish(make_error(std::string("unexpected message from the server: ") + message_name(m)));
    }
}

// The result channel: its name checked, the dump opened when one is written.
void ClientSession::on_result_open(const OpenChannelMsg& open) {
    auto name = ChannelName::parse(open.name);
    if (!name || name->version != kLightcutsVersionGuid || name->extension != kLightcutsExtension)
        return finish(make_error("server opened an unexpected channel '" + open.name +
                                 "' (expected version " + kLightcutsVersionGuid.to_hex() + ", extension ." +
                                 kLightcutsExtension + ")"));
    if (result_channel_id_) return finish(make_error("server opened a second result channel"));
    result_channel_id_ = open.channel_id;
    outcome_.result_channel_name = open.name;
    expected_bytes_ = open.total_bytes;
    download_start_ = Clock::now();
    if (options_.write_dump) {
        actions_.push_back(client_action::OpenDump{open.name, open.total_bytes});
        dump_open_ = true;
    }
}

// A chunk of the result: in order, within the announced size, its records
// valid; appended to the dump and kept where the outcome or a recording needs it.
void ClientSession::on_result_write(const WriteChannelMsg& write) {
    if (!result_channel_id_ || write.channel_id != *result_channel_id_)
        return finish(
            make_error("server wrote to channel " + std::to_string(write.channel_id) + " which is not open"));
    const std::span<const uint8_t> data = write.bytes();
    if (write.offset != result_received_ || result_received_ + data.size() > expected_bytes_)
        return finish(make_error("result channel out of order or longer than announced"));
    if (Status s = reader_.consume(data); !s) return finish(make_error("result channel: " + s.error()));
    result_received_ += data.size();
    if (dump_open_) actions_.push_back(client_action::AppendDump{data});
    if (options_.keep_result_channel || options_.record_channels)
        result_bytes_.insert(result_bytes_.end(), data.begin(), data.end());
    if (reader_.nodes_expected() > 0) {
        float pct = 100.0f * static_cast<float>(reader_.nodes_received()) /
                    static_cast<float>(reader_.nodes_expected());
        actions_.push_back(
            client_action::ReportProgress{ProgressMsg{options_.request.bake_id, "receiving", pct}});
    }
}

// The tree complete and as large as BakeDone says: the outcome, recorded and
// its dump committed where asked.
void ClientSession::on_bake_done(const BakeDoneMsg& done) {
    if (!channel_closed_) return finish(make_error("BakeDone arrived before the result channel was closed"));
    const size_t node_count = reader_.nodes_received();
    const Clock::time_point import_start = Clock::now();
    if (options_.decode_tree) {
        Result<LightTree> tree = reader_.finish();
        if (!tree) return finish(make_error("result channel: " + tree.error()));
        outcome_.tree = std::move(tree.value());
    } else if (Status valid = reader_.finish_validation(); !valid) {
        return finish(make_error("result channel: " + valid.error()));
    }
    outcome_.import_ms = ms_since(import_start);
    if (node_count != done.node_count)
        return finish(make_error("BakeDone announces " + std::to_string(done.node_count) +
                                 " nodes, channel held " + std::to_string(node_count)));
    outcome_.done = done;
    outcome_.download_ms = ms_since(download_start_);
    if (options_.record_channels) {
        // Kept for the outcome too: the recording gets a copy (--record is for tests' data).
        std::vector<uint8_t> recorded =
            options_.keep_result_channel ? result_bytes_ : std::move(result_bytes_);
        actions_.push_back(client_action::RecordChannel{outcome_.result_channel_name, std::move(recorded)});
    }
    if (options_.keep_result_channel) outcome_.result_channel = std::move(result_bytes_);
    result_bytes_ = std::vector<uint8_t>();
    if (dump_open_) {
        actions_.push_back(client_action::CommitDump{});
        dump_open_ = false;
        dump_committing_ = true;
    }
    finish(std::move(outcome_));
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

void ClientSession::fail_outputs(Error error) {
    finish(std::move(error));
}

void ClientSession::finish(Result<BakeOutcome> result) {
    stage_ = Stage::kFinished;
    outbox_.clear();
    // A failed bake's dump is never committed: its temporary file goes. A
    // commit the I/O layer had not reached when an earlier action failed counts as open.
    if (!result && (dump_open_ || dump_committing_)) actions_.push_back(client_action::DiscardDump{});
    dump_open_ = false;
    if (!result) dump_committing_ = false;
    result_.emplace(std::move(result));
}

Result<BakeOutcome> ClientSession::take_result() {
    if (!result_) return make_error("the bake has not finished");
    Result<BakeOutcome> result = std::move(*result_);
    result_.reset();
    return result;
}

}  // namespace lc::client
