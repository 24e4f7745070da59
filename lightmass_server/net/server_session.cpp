#include "lightmass_server/net/server_session.h"

#include <spdlog/spdlog.h>

#include <utility>

#include "lightmass_server/net/auth_token.h"
#include "lightmass_server/bake/bake_footprint.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/indirect/patch_mesh.h"
#include "lightmass_server/bake/result_channel_file.h"
#include "protocol/bake_limits.h"
#include "lightcuts/version.h"
#include "protocol/channel_name.h"

namespace lc::bake {

ServerSession::ServerSession(ServerSessionOptions options) : options_(std::move(options)) {}

ServerActions ServerSession::take_actions() { return std::exchange(actions_, {}); }

void ServerSession::send(Message message) { actions_.push_back(SendMessage{std::move(message)}); }

void ServerSession::send_error(uint32_t bake_id, ErrorCode code, const std::string& text) {
    spdlog::warn("connection {}: error sent: {}", options_.connection_id, text);
    send(ErrorMsg{bake_id, code, text});
}

ServerActions ServerSession::on_message(Message message) {
    if (closing_) return {};
    bool keep = true;
    if (!greeted_ && !std::holds_alternative<HelloMsg>(message)) {
        send_error(0, ErrorCode::kMalformedFrame,
                   std::string("expected Hello as the first message, got ") + message_name(message));
        keep = false;
    } else if (auto* hello = std::get_if<HelloMsg>(&message)) {
        keep = on_hello(*hello);
    } else if (auto* open = std::get_if<OpenChannelMsg>(&message)) {
        keep = on_open_channel(*open);
    } else if (auto* write = std::get_if<WriteChannelMsg>(&message)) {
        keep = on_write_channel(*write);
    } else if (auto* close = std::get_if<CloseChannelMsg>(&message)) {
        keep = on_close_channel(*close);
    } else if (auto* request = std::get_if<BakeRequestMsg>(&message)) {
        keep = on_bake_request(*request);
    } else if (auto* cancel = std::get_if<CancelMsg>(&message)) {
        on_cancel(*cancel);
    } else if (auto* status = std::get_if<StatusRequestMsg>(&message)) {
        on_status_request(*status);
    } else {
        send_error(0, ErrorCode::kMalformedFrame,
                   std::string("a client may not send ") + message_name(message) + " messages");
        keep = false;
    }
    if (!keep) close_after_flush("protocol violation");
    return take_actions();
}

ServerActions ServerSession::on_malformed_frame(const std::string& error) {
    if (closing_) return {};
    send_error(0, ErrorCode::kMalformedFrame, "malformed frame: " + error);
    close_after_flush("malformed frame");
    return take_actions();
}

ServerActions ServerSession::on_bad_frame_header(const std::string& error) {
    if (closing_) return {};
    send_error(0, ErrorCode::kTooLarge, "bad frame header: " + error);
    close_after_flush("bad frame header");
    return take_actions();
}

ServerActions ServerSession::on_server_stopping(const std::string& reason) {
    if (closing_) return {};
    if (bake_)
        // Not kCancelled: the client says "cancelled" for its own cancel, without our reason.
        send_error(bake_->bake_id, ErrorCode::kBakeFailed,
                   "bake " + std::to_string(bake_->bake_id) + " stopped: " + reason);
    close_after_flush(reason);
    return take_actions();
}

void ServerSession::close_after_flush(std::string reason) {
    ServerActions cancel = on_closing();
    actions_.insert(actions_.end(), cancel.begin(), cancel.end());
    actions_.push_back(CloseAfterFlush{std::move(reason)});
}

ServerActions ServerSession::on_closing() {
    if (closing_) return {};
    closing_ = true;
    incoming_.clear();  // half-received channels give their reservations back now
    if (bake_ && !bake_->streaming && !bake_->cancel_requested) {
        bake_->cancel_requested = true;
        return {CancelBake{bake_->bake_id}};
    }
    return {};
}

bool ServerSession::on_hello(const HelloMsg& hello) {
    if (greeted_) {
        send_error(0, ErrorCode::kMalformedFrame, "Hello sent twice");
        return false;
    }
    if (hello.protocol_version != kProtocolVersion) {
        send_error(0, ErrorCode::kVersionMismatch,
                   "protocol version mismatch: client speaks " + hello.protocol_version.to_hex() +
                       ", server speaks " + kProtocolVersion.to_hex());
        return false;
    }
    if (!options_.busy_reason.empty()) {
        send_error(0, ErrorCode::kBusy, "server busy: " + options_.busy_reason);
        return false;
    }
    if (options_.token && !tokens_equal(*options_.token, hello.token)) {
        send_error(0, ErrorCode::kAuthentication,
                   hello.token.empty() ? "this server requires a token (client: --token-file FILE)"
                                       : "authentication failed: the token does not match");
        return false;
    }
    greeted_ = true;
    spdlog::info("connection {}: hello from '{}'", options_.connection_id, hello.peer_name);
    send(HelloAckMsg{kProtocolVersion, std::string("lightmass_server ") + kVersion});
    return true;
}

bool ServerSession::on_open_channel(const OpenChannelMsg& open) {
    if (incoming_.count(open.channel_id) || refused_.count(open.channel_id)) {
        send_error(0, ErrorCode::kMalformedFrame,
                   "channel id " + std::to_string(open.channel_id) + " is already open");
        return false;
    }
    auto refuse = [&](ErrorCode code, const std::string& text) {
        refused_.insert(open.channel_id);
        send_error(0, code, "channel '" + open.name + "' refused: " + text);
        return true;
    };
    auto name = ChannelName::parse(open.name);
    if (!name) return refuse(ErrorCode::kUnknownChannel, "not a VERSION.GUID.ext channel name");
    const std::optional<ChannelKind> kind = channel_kind_of_extension(name->extension);
    if (!kind)
        return refuse(ErrorCode::kUnknownChannel, "this server accepts only ." + std::string(kSceneExtension) +
                                                      ", ." + kGeometryExtension + " and ." +
                                                      kEnvironmentChannelExtension + " channels, got ." +
                                                      name->extension);
    if (name->version != kSceneFormatVersionGuid)
        return refuse(ErrorCode::kVersionMismatch, "scene format version " + name->version.to_hex() +
                                                       " is not supported; this server reads " +
                                                       kSceneFormatVersionGuid.to_hex());
    const ChannelLimit limit = channel_limit(*kind);
    if (open.total_bytes > limit.max_bytes)
        return refuse(ErrorCode::kTooLarge, "announces " + std::to_string(open.total_bytes) +
                                                " bytes; the limit is " + std::to_string(limit.max_bytes) + " (" +
                                                limit.words + ")");
    if (incoming_.size() >= kMaxOpenChannels)
        return refuse(ErrorCode::kBusy, "too many channels open at once (limit " +
                                            std::to_string(kMaxOpenChannels) + ")");
    const uint64_t cap = options_.max_connection_channel_bytes;
    if (cap != 0 && open.total_bytes > cap - std::min(cap, open_channel_bytes()))
        return refuse(ErrorCode::kBusy, "this connection's open channels would hold " +
                                            std::to_string(open_channel_bytes() + open.total_bytes) +
                                            " bytes, more than its cap of " + std::to_string(cap) +
                                            " (half of --memory-budget-mb); close one first");
    MemoryBudget* budget = options_.memory_budget;
    if (budget && !budget->try_reserve(open.total_bytes))
        return refuse(ErrorCode::kBusy, "server busy: " + std::to_string(open.total_bytes) +
                                            " bytes do not fit in the memory budget (" +
                                            std::to_string(budget->used()) + " of " +
                                            std::to_string(budget->limit()) + " bytes in use; --memory-budget-mb)");
    incoming_.try_emplace(open.channel_id, open.name, *kind, open.total_bytes,
                          BudgetReservation(budget, open.total_bytes));
    return true;
}

uint64_t ServerSession::stored_channel_bytes() const {
    uint64_t bytes = 0;
    for (const auto& [name, scene] : scenes_) bytes += scene.reservation.bytes();
    for (const auto& [name, environment] : environments_) bytes += environment.reservation.bytes();
    for (const auto& [name, geometry] : geometries_) bytes += geometry.reservation.bytes();
    return bytes;
}

uint64_t ServerSession::open_channel_bytes() const {
    uint64_t bytes = 0;
    for (const auto& [id, channel] : incoming_) bytes += channel.total_bytes();
    return bytes;
}

bool ServerSession::on_write_channel(WriteChannelMsg& write) {
    if (refused_.count(write.channel_id)) return true;  // already answered with an error
    auto it = incoming_.find(write.channel_id);
    if (it == incoming_.end()) {
        send_error(0, ErrorCode::kUnknownChannel,
                   "write to channel id " + std::to_string(write.channel_id) + " which is not open");
        return false;
    }
    IncomingChannel& channel = it->second;
    if (write.offset != channel.received()) {
        send_error(0, ErrorCode::kMalformedFrame,
                   "channel '" + channel.name() + "': write at offset " + std::to_string(write.offset) +
                       ", expected " + std::to_string(channel.received()));
        return false;
    }
    if (Status consumed = channel.consume(write.bytes(), options_.record_channels); !consumed) {
        send_error(0, ErrorCode::kInvalidScene, channel.label() + ": " + consumed.error());
        refused_.insert(write.channel_id);
        incoming_.erase(it);
    }
    return true;
}

bool ServerSession::on_close_channel(const CloseChannelMsg& close) {
    if (refused_.erase(close.channel_id)) return true;
    auto it = incoming_.find(close.channel_id);
    if (it == incoming_.end()) {
        send_error(0, ErrorCode::kUnknownChannel,
                   "close of channel id " + std::to_string(close.channel_id) + " which is not open");
        return false;
    }
    IncomingChannel channel = std::move(it->second);
    incoming_.erase(it);
    if (!channel.complete()) {
        send_error(0, ErrorCode::kInvalidScene,
                   channel.label() + " closed after " + std::to_string(channel.received()) + " of " +
                       std::to_string(channel.total_bytes()) + " bytes");
        return true;
    }
    switch (channel.kind()) {
        case ChannelKind::kScene: store_scene(channel); break;
        case ChannelKind::kGeometry: store_geometry(channel); break;
        case ChannelKind::kEnvironment: store_environment(channel); break;
    }
    return true;
}

// The oldest of `stored` makes room when it holds kMaxStoredScenes others.
template <typename Stored>
static void store_channel(std::map<std::string, Stored>& stored, const std::string& name, Stored value) {
    if (stored.size() >= kMaxStoredScenes && !stored.count(name)) stored.erase(stored.begin());
    stored[name] = std::move(value);
}

void ServerSession::store_scene(IncomingChannel& channel) {
    Result<std::vector<SceneLight>> lights = std::get<SceneChannelReader>(channel.reader()).finish();
    if (!lights) {
        send_error(0, ErrorCode::kInvalidScene, channel.label() + ": " + lights.error());
        return;
    }
    if (options_.record_channels) actions_.push_back(RecordChannel{channel.name(), channel.take_recorded()});
    spdlog::info("connection {}: scene '{}' received, {} lights", options_.connection_id, channel.name(),
                 lights->size());
    store_channel(scenes_, channel.name(), StoredScene{std::move(lights.value()), channel.take_reservation()});
}

void ServerSession::store_environment(IncomingChannel& channel) {
    Result<Environment> environment = std::get<EnvironmentChannelReader>(channel.reader()).finish();
    if (!environment) {
        send_error(0, ErrorCode::kInvalidScene, channel.label() + ": " + environment.error());
        return;
    }
    if (options_.record_channels) actions_.push_back(RecordChannel{channel.name(), channel.take_recorded()});
    spdlog::info("connection {}: environment '{}' received, {}", options_.connection_id, channel.name(),
                 environment->has_sky() ? std::string("a sun and sky")
                                        : std::to_string(environment->map.width) + " x " +
                                              std::to_string(environment->map.height) + " map");
    store_channel(environments_, channel.name(),
                  StoredEnvironment{std::make_shared<const Environment>(std::move(environment.value())),
                                    channel.take_reservation()});
}

void ServerSession::store_geometry(IncomingChannel& channel) {
    GeometryChannelReader& reader = std::get<GeometryChannelReader>(channel.reader());
    const size_t degenerate = reader.degenerate_skipped();
    Result<SceneGeometry> geometry = reader.finish();
    if (!geometry) {
        send_error(0, ErrorCode::kInvalidScene, channel.label() + ": " + geometry.error());
        return;
    }
    if (options_.record_channels) actions_.push_back(RecordChannel{channel.name(), channel.take_recorded()});
    if (degenerate > 0) {
        send(WarningMsg{0, channel.label() + ": " + std::to_string(degenerate) +
                               " degenerate triangles (zero or non-finite area) skipped"});
    }
    spdlog::info("connection {}: geometry '{}' received, {} triangles, {} materials", options_.connection_id,
                 channel.name(), geometry->triangles.size(), geometry->materials.size());
    store_channel(geometries_, channel.name(),
                  StoredGeometry{std::make_shared<const SceneGeometry>(std::move(geometry.value())),
                                 channel.take_reservation()});
}

bool ServerSession::check_bake_request(const BakeRequestMsg& request) {
    if (Status settings = validate_bake_settings(request); !settings) {
        send_error(request.bake_id, ErrorCode::kInvalidScene,
                   "bake " + std::to_string(request.bake_id) + " refused: " + settings.error());
        return false;
    }
    if (request.indirect.method != IndirectMethod::kRadiosity || request.geometry_channel.empty())
        return true;
    auto geometry = geometries_.find(request.geometry_channel);
    if (geometry == geometries_.end()) return true;  // named in the next check
    Status patches =
        check_patch_count(*geometry->second.geometry, request.indirect.patch_size, kMaxRadiosityPatches);
    if (!patches) send_error(request.bake_id, ErrorCode::kTooLarge, patches.error());
    return patches.ok();
}

template <typename Stored>
const Stored* ServerSession::find_stored(const std::map<std::string, Stored>& stored, const std::string& name,
                                         ChannelKind kind, uint32_t bake_id) {
    auto it = stored.find(name);
    if (it != stored.end()) return &it->second;
    send_error(bake_id, ErrorCode::kUnknownChannel,
               std::string("no complete ") + channel_kind_name(kind) + " channel named '" + name +
                   "' (open, write and close it before BakeRequest)");
    return nullptr;
}

bool ServerSession::on_bake_request(const BakeRequestMsg& request) {
    if (bake_) {
        send_error(request.bake_id, ErrorCode::kBusy,
                   "bake " + std::to_string(bake_->bake_id) + " is still running on this connection");
        return true;
    }
    if (!check_bake_request(request)) return true;
    const StoredScene* scene = find_stored(scenes_, request.scene_channel, ChannelKind::kScene, request.bake_id);
    if (!scene) return true;
    std::shared_ptr<const Environment> environment;
    if (!request.environment_channel.empty()) {
        const StoredEnvironment* stored =
            find_stored(environments_, request.environment_channel, ChannelKind::kEnvironment, request.bake_id);
        if (!stored) return true;
        environment = stored->environment;
        if (request.environment_lights != 0) {
            Status count = validate_environment_light_count(*environment, request.environment_lights);
            if (!count) {
                send_error(request.bake_id, ErrorCode::kInvalidScene, count.error());
                return true;
            }
        }
    }
    std::shared_ptr<const SceneGeometry> geometry;
    if (!request.geometry_channel.empty()) {
        const StoredGeometry* stored =
            find_stored(geometries_, request.geometry_channel, ChannelKind::kGeometry, request.bake_id);
        if (!stored) return true;
        geometry = stored->geometry;
    }
    auto lights = std::make_shared<std::vector<SceneLight>>();
    size_t classic = 0;
    for (const SceneLight& light : scene->lights) {
        if (light.classic) ++classic;
        else lights->push_back(light);
    }

    StartBake start;
    start.bake_id = request.bake_id;
    BuildOptions& build = start.inputs.build;
    build.builder = request.builder;
    build.representative_rule = request.representative_rule;
    build.pairing = request.pairing;
    build.seed = request.seed;
    if (request.exact_pairing_limit != 0) build.exact_pairing_limit = request.exact_pairing_limit;
    start.inputs.indirect = indirect_options(request.indirect, request.seed);
    start.inputs.lights = std::move(lights);
    start.inputs.geometry = std::move(geometry);
    if (request.area_lights != 0) start.inputs.area_lights = request.area_lights;
    start.inputs.environment = std::move(environment);
    start.inputs.environment_lights = request.environment_lights;
    start.inputs.ranks = request.ranks;
    BudgetReservation reservation;
    if (!reserve_bake(request.bake_id, start, reservation)) return true;

    if (classic > 0)
        send(WarningMsg{
            request.bake_id,
            std::to_string(classic) + " classic lights in the scene channel were left out of the tree"});
    spdlog::info("connection {}: bake {} of {} lights{} with {} (seed {})", options_.connection_id,
                 request.bake_id, start.inputs.lights->size(), start.inputs.geometry ? " and geometry" : "",
                 builder_name(build.builder), build.seed);
    bake_ = ActiveBake{request.bake_id, false, false, std::move(reservation), request.ranks, {}};
    send(ProgressMsg{request.bake_id, "queued", 0.0f});
    actions_.push_back(std::move(start));
    return true;
}

bool ServerSession::reserve_bake(uint32_t bake_id, StartBake& start, BudgetReservation& reservation) {
    const BakeFootprint footprint = estimate_bake_footprint(start.inputs, options_.record_channels);
    start.inputs.indirect.vpl.max_lights = footprint.max_vpls;
    // A bake over ranks waits on its MPI job for its whole length: never on the small lane.
    start.small = footprint.bytes <= kSmallBakeBytes && start.inputs.indirect.method == IndirectMethod::kOff &&
                  start.inputs.ranks == 0;
    MemoryBudget* budget = options_.memory_budget;
    if (!budget) return true;
    if (footprint.bytes > budget->limit()) {
        send_error(bake_id, ErrorCode::kTooLarge,
                   "bake " + std::to_string(bake_id) + " too large: needs " +
                       megabytes_text(footprint.bytes) + " (" + footprint.largest + "), the budget is " +
                       megabytes_text(budget->limit()) + " (--memory-budget-mb)");
        return false;
    }
    if (!budget->try_reserve(footprint.bytes)) {
        send_error(bake_id, ErrorCode::kBusy,
                   "server busy: bake " + std::to_string(bake_id) + " needs " +
                       megabytes_text(footprint.bytes) + " and " +
                       megabytes_text(budget->limit() - std::min(budget->limit(), budget->used())) +
                       " of the " + megabytes_text(budget->limit()) + " budget is free; try again later");
        return false;
    }
    reservation = BudgetReservation(budget, footprint.bytes);
    spdlog::info("connection {}: bake {} reserves {} ({} tree lights at most) beside {} of stored channels",
                 options_.connection_id, bake_id, megabytes_text(footprint.bytes), footprint.tree_lights,
                 megabytes_text(stored_channel_bytes()));
    return true;
}

void ServerSession::on_cancel(const CancelMsg& cancel) {
    if (!bake_ || bake_->bake_id != cancel.bake_id) return;  // finished already, or never started
    if (bake_->streaming) {
        // Already built: stop streaming, the client discards the partial channel.
        bake_.reset();
        actions_.push_back(StopStream{});
        send_error(cancel.bake_id, ErrorCode::kCancelled,
                   "bake " + std::to_string(cancel.bake_id) + " cancelled during transfer");
        return;
    }
    if (bake_->cancel_requested) return;
    bake_->cancel_requested = true;
    actions_.push_back(CancelBake{cancel.bake_id});
}

void ServerSession::on_status_request(const StatusRequestMsg& request) {
    StatusReplyMsg reply = options_.status ? options_.status() : StatusReplyMsg{};
    reply.request_id = request.request_id;
    send(std::move(reply));
}

std::optional<BakeStatusEntry> ServerSession::bake_status() const {
    if (!bake_) return std::nullopt;
    BakeStatusEntry entry;
    entry.connection = options_.connection_id;
    entry.bake_id = bake_->bake_id;
    entry.state = bake_->streaming ? "streaming" : bake_->latest.stage.empty() ? "queued" : "running";
    entry.stage = bake_->streaming ? "streaming" : bake_->latest.stage;
    entry.percent = bake_->streaming ? 100.0f : bake_->latest.percent;
    entry.ranks = bake_->ranks;
    return entry;
}

ServerActions ServerSession::on_bake_progress(const ProgressMsg& progress) {
    if (closing_ || !bake_ || bake_->bake_id != progress.bake_id || bake_->streaming) return {};
    bake_->latest = progress;
    send(progress);
    return take_actions();
}

ServerActions ServerSession::on_bake_finished(uint32_t bake_id, Result<BuildResult> result) {
    if (closing_ || !bake_ || bake_->bake_id != bake_id || bake_->streaming) return {};
    if (!result) {
        if (result.error_kind() == ErrorKind::kCancelled || bake_->cancel_requested)
            send_error(bake_id, ErrorCode::kCancelled, "bake " + std::to_string(bake_id) + " cancelled");
        else
            send_error(bake_id, ErrorCode::kBakeFailed,
                       "bake " + std::to_string(bake_id) + " failed: " + result.error());
        bake_.reset();
        return take_actions();
    }
    BuildResult built = std::move(result.value());
    for (const std::string& warning : built.report.warnings) send(WarningMsg{bake_id, warning});
    // A bake over MPI ranks leaves its tree on disk: streamed from there, never decoded here.
    std::shared_ptr<const LightTree> tree;
    if (!built.channel_file) tree = std::make_shared<const LightTree>(std::move(built.tree));
    BakeDoneMsg done;
    done.bake_id = bake_id;
    done.result_channel = lightcuts_result_channel_name();
    done.node_count = tree ? static_cast<uint32_t>(tree->nodes.size()) : built.channel_file->node_count();
    done.leaf_count = tree ? tree->leaf_count : built.channel_file->leaf_count();
    done.build_ms = built.report.build_ms;
    done.pairing_cost = built.report.pairing_cost;
    done.pairing_lower_bound = built.report.pairing_lower_bound;
    done.exact = built.report.exact;
    done.effects = built.report.effects;
    done.lights = built.report.lights;
    spdlog::info("connection {}: bake {} built {} nodes in {:.1f} ms", options_.connection_id, bake_id,
                 done.node_count, done.build_ms);
    if (options_.record_channels) record_result(done.result_channel, tree, built.channel_file);
    send(ProgressMsg{bake_id, "streaming", 100.0f});
    bake_->streaming = true;
    actions_.push_back(
        StreamResult{std::move(tree), std::move(built.channel_file), next_channel_id_++, std::move(done)});
    return take_actions();
}

void ServerSession::record_result(const std::string& name, const std::shared_ptr<const LightTree>& tree,
                                  const std::shared_ptr<const ResultChannelFile>& file) {
    if (tree) {
        actions_.push_back(RecordChannel{name, encode_result_channel(*tree)});
        return;
    }
    std::vector<uint8_t> bytes(file->size_bytes());  // --record is for debugging: the whole channel
    if (Status read = file->read(0, bytes); !read) {
        spdlog::warn("connection {}: the result was not recorded: {}", options_.connection_id, read.error());
        return;
    }
    actions_.push_back(RecordChannel{name, std::move(bytes)});
}

void ServerSession::on_result_delivered() {
    if (!bake_ || !bake_->streaming) return;
    spdlog::info("connection {}: bake {} delivered", options_.connection_id, bake_->bake_id);
    bake_.reset();
}

}  // namespace lc::bake
