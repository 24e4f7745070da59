#include "editor_client/bake/client_session.h"


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
      download_(options_.decode_tree ? TreeImport::kNodes : TreeImport::kValidateOnly,
                options_.keep_result_channel || options_.record_channels) {}

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
    if (!upload_) {
        upload_start_ = Clock::now();
        upload_.emplace(start_upload());
    }
    if (std::optional<Message> message = upload_->next_message()) return message;
    // Recorded before BakeRequest is sent: a recording that fails ends the bake first.
    if (options_.record_channels) {
        for (UploadChannel& channel : upload_->take_channels())
            actions_.push_back(client_action::RecordChannel{channel.name, std::move(channel.bytes)});
    }
    upload_.reset();
    stage_ = Stage::kBaking;
    outcome_.upload_ms = ms_since(upload_start_);
    return bake_request();
}

ChannelUpload ClientSession::start_upload() {
    std::vector<UploadChannel> channels;
    channels.push_back({kSceneChannelId, scene_channel_, encode_scene_channel(lights_)});
    // A new vector, not `= {}`: that clears and keeps the million lights' capacity.
    lights_ = std::vector<SceneLight>();
    if (options_.geometry) {
        channels.push_back({kGeometryChannelId, geometry_channel_, encode_geometry_channel(*options_.geometry)});
        options_.geometry.reset();
    }
    if (options_.environment)
        channels.push_back(
            {kEnvironmentChannelId, environment_channel_, encode_environment_channel(*options_.environment)});
    return ChannelUpload(std::move(channels), options_.chunk_bytes);
}

BakeRequestMsg ClientSession::bake_request() {
    BakeRequestMsg request = options_.request;
    request.scene_channel = scene_channel_;
    request.environment_channel = options_.environment ? environment_channel_ : std::string();
    request.geometry_channel = geometry_channel_;
    return request;
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
        if (Status closed = download_.close(*close); !closed) finish(closed.failure());
    } else if (auto* done = std::get_if<BakeDoneMsg>(&m)) {
        on_bake_done(*done);
    } else {
        finish(make_error(std::string("unexpected message from the server: ") + message_name(m)));
    }
}

// The result channel: its name checked, the dump opened when one is written.
void ClientSession::on_result_open(const OpenChannelMsg& open) {
    if (Status opened = download_.open(open); !opened) return finish(opened.failure());
    outcome_.result_channel_name = open.name;
    if (options_.write_dump) {
        actions_.push_back(client_action::OpenDump{open.name, open.total_bytes});
        dump_ = Dump::kOpen;
    }
}

// A chunk of the result, appended to the dump; the share of nodes received reported.
void ClientSession::on_result_write(const WriteChannelMsg& write) {
    Result<std::span<const uint8_t>> data = download_.write(write);
    if (!data) return finish(data.failure());
    if (dump_ == Dump::kOpen) actions_.push_back(client_action::AppendDump{*data});
    if (std::optional<float> percent = download_.percent())
        actions_.push_back(
            client_action::ReportProgress{ProgressMsg{options_.request.bake_id, "receiving", *percent}});
}

// The tree complete and as large as BakeDone says: the outcome, recorded and
// its dump committed where asked.
void ClientSession::on_bake_done(const BakeDoneMsg& done) {
    if (!download_.closed()) return finish(make_error("BakeDone arrived before the result channel was closed"));
    ResultChannelReader& reader = download_.reader();
    const size_t node_count = reader.nodes_received();
    const Clock::time_point import_start = Clock::now();
    if (options_.decode_tree) {
        Result<LightTree> tree = reader.finish();
        if (!tree) return finish(make_error("result channel: " + tree.error()));
        outcome_.tree = std::move(tree.value());
    } else if (Status valid = reader.finish_validation(); !valid) {
        return finish(make_error("result channel: " + valid.error()));
    }
    outcome_.import_ms = ms_since(import_start);
    if (node_count != done.node_count)
        return finish(make_error("BakeDone announces " + std::to_string(done.node_count) +
                                 " nodes, channel held " + std::to_string(node_count)));
    outcome_.done = done;
    outcome_.download_ms = download_.ms_since_open();
    std::vector<uint8_t> bytes = download_.take_bytes();
    if (options_.record_channels) {
        // Kept for the outcome too: the recording gets a copy (--record is for tests' data).
        std::vector<uint8_t> recorded = options_.keep_result_channel ? bytes : std::move(bytes);
        actions_.push_back(client_action::RecordChannel{outcome_.result_channel_name, std::move(recorded)});
    }
    if (options_.keep_result_channel) outcome_.result_channel = std::move(bytes);
    if (dump_ == Dump::kOpen) {
        actions_.push_back(client_action::CommitDump{});
        dump_ = Dump::kCommitting;
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
    if (!result && dump_ != Dump::kNone) actions_.push_back(client_action::DiscardDump{});
    if (!result) dump_ = Dump::kNone;
    result_.emplace(std::move(result));
}

Result<BakeOutcome> ClientSession::take_result() {
    if (!result_) return make_error("the bake has not finished");
    Result<BakeOutcome> result = std::move(*result_);
    result_.reset();
    return result;
}

}  // namespace lc::client
