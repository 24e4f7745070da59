// The server's protocol state machine with no socket: messages in, messages
// and actions out. Every outcome is checked by its ErrorCode, never its text.
#include <gtest/gtest.h>

#include <vector>

#include "lightmass_server/bake/bake_footprint.h"
#include "lightmass_server/net/server_session.h"
#include "protocol/bake_limits.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/geometry_channel.h"
#include "tree_invariants.h"

namespace lc::bake {
namespace {

constexpr Guid kSceneGuid{0x11111111u, 0x22222222u, 0x33333333u, 0x44444444u};
constexpr uint32_t kChannel = 1;
constexpr uint32_t kBake = 7;

std::vector<SceneLight> scene_lights() { return test::random_lights(8, 3, LightType::kPoint); }

std::vector<Message> sent(const ServerActions& actions) {
    std::vector<Message> messages;
    for (const ServerAction& action : actions)
        if (auto* send = std::get_if<SendMessage>(&action)) messages.push_back(send->message);
    return messages;
}

template <typename T>
size_t count_of(const ServerActions& actions) {
    size_t n = 0;
    for (const ServerAction& action : actions) n += std::holds_alternative<T>(action) ? 1 : 0;
    return n;
}

template <typename T>
const T* first_of(const ServerActions& actions) {
    for (const ServerAction& action : actions)
        if (auto* found = std::get_if<T>(&action)) return found;
    return nullptr;
}

// The codes of the errors sent, in order.
std::vector<ErrorCode> error_codes(const ServerActions& actions) {
    std::vector<ErrorCode> codes;
    for (const Message& message : sent(actions))
        if (auto* error = std::get_if<ErrorMsg>(&message)) codes.push_back(error->code);
    return codes;
}

bool closes(const ServerActions& actions) { return count_of<CloseAfterFlush>(actions) == 1; }

ServerActions hello(ServerSession& session, const std::string& token = "", Guid version = kProtocolVersion) {
    return session.on_message(HelloMsg{version, "test client", token});
}

BakeRequestMsg bake_request(uint32_t bake_id = kBake) {
    BakeRequestMsg request;
    request.bake_id = bake_id;
    request.scene_channel = scene_channel_name(kSceneGuid);
    return request;
}

// Opens and writes the scene channel (without closing it); returns every action.
ServerActions open_and_write(ServerSession& session, const std::vector<SceneLight>& lights) {
    const std::vector<uint8_t> bytes = encode_scene_channel(lights);
    ServerActions all = session.on_message(OpenChannelMsg{kChannel, scene_channel_name(kSceneGuid), bytes.size()});
    ServerActions written = session.on_message(WriteChannelMsg{kChannel, 0, bytes});
    all.insert(all.end(), written.begin(), written.end());
    return all;
}

// A greeted session holding the complete scene channel.
ServerSession session_with_scene(ServerSessionOptions options = {}) {
    ServerSession session(std::move(options));
    EXPECT_EQ(sent(hello(session)).size(), 1u);
    EXPECT_TRUE(error_codes(open_and_write(session, scene_lights())).empty());
    EXPECT_TRUE(error_codes(session.on_message(CloseChannelMsg{kChannel})).empty());
    return session;
}

Result<BuildResult> built_tree() { return build_light_tree(scene_lights(), BuildOptions{}, nullptr); }

TEST(ServerSession, AnswersHelloOnceAndClosesOnADuplicate) {
    ServerSession session({});
    ServerActions first = hello(session);
    ASSERT_EQ(sent(first).size(), 1u);
    EXPECT_TRUE(std::holds_alternative<HelloAckMsg>(sent(first)[0]));
    EXPECT_TRUE(session.greeted());

    ServerActions second = hello(session);
    EXPECT_EQ(error_codes(second), std::vector<ErrorCode>{ErrorCode::kMalformedFrame});
    EXPECT_TRUE(closes(second));
    // Closing: nothing more is answered.
    EXPECT_TRUE(session.on_message(bake_request()).empty());
}

TEST(ServerSession, FirstMessageMustBeHello) {
    ServerSession session({});
    ServerActions actions = session.on_message(bake_request());
    EXPECT_EQ(error_codes(actions), std::vector<ErrorCode>{ErrorCode::kMalformedFrame});
    EXPECT_TRUE(closes(actions));
    EXPECT_EQ(count_of<StartBake>(actions), 0u);
}

TEST(ServerSession, VersionMismatchIsRefusedWithItsCode) {
    ServerSession session({});
    Guid other = kProtocolVersion;
    other.d += 1;
    ServerActions actions = hello(session, "", other);
    EXPECT_EQ(error_codes(actions), std::vector<ErrorCode>{ErrorCode::kVersionMismatch});
    EXPECT_TRUE(closes(actions));
    EXPECT_FALSE(session.greeted());
}

TEST(ServerSession, TokenIsRequiredAndMustMatch) {
    ServerSessionOptions options;
    options.token = "secret";
    for (const std::string& token : {std::string(), std::string("wrong")}) {
        ServerSession session(options);
        ServerActions actions = hello(session, token);
        EXPECT_EQ(error_codes(actions), std::vector<ErrorCode>{ErrorCode::kAuthentication}) << token;
        EXPECT_TRUE(closes(actions));
    }
    ServerSession session(options);
    ServerActions accepted = hello(session, "secret");
    ASSERT_EQ(sent(accepted).size(), 1u);
    EXPECT_TRUE(std::holds_alternative<HelloAckMsg>(sent(accepted)[0]));
}

TEST(ServerSession, BakeBeforeTheSceneChannelIsClosedNamesTheChannel) {
    ServerSession session({});
    hello(session);
    open_and_write(session, scene_lights());
    EXPECT_FALSE(session.idle());  // a channel is half-received
    ServerActions early = session.on_message(bake_request());
    EXPECT_EQ(error_codes(early), std::vector<ErrorCode>{ErrorCode::kUnknownChannel});
    EXPECT_EQ(std::get<ErrorMsg>(sent(early)[0]).bake_id, kBake);
    EXPECT_EQ(count_of<StartBake>(early), 0u);
    EXPECT_FALSE(closes(early));

    session.on_message(CloseChannelMsg{kChannel});
    ServerActions started = session.on_message(bake_request());
    EXPECT_TRUE(error_codes(started).empty());
    const StartBake* start = first_of<StartBake>(started);
    ASSERT_NE(start, nullptr);
    EXPECT_EQ(start->bake_id, kBake);
    EXPECT_EQ(start->inputs.lights->size(), 8u);
}

TEST(ServerSession, UnknownChannels) {
    ServerSession session({});
    hello(session);
    // A channel of another kind is refused; its writes are dropped and its close accepted.
    const std::string image = create_channel_name(kSceneGuid, kSceneFormatVersionGuid, "png");
    ServerActions refused = session.on_message(OpenChannelMsg{2, image, 16});
    EXPECT_EQ(error_codes(refused), std::vector<ErrorCode>{ErrorCode::kUnknownChannel});
    EXPECT_FALSE(closes(refused));
    EXPECT_TRUE(session.on_message(WriteChannelMsg{2, 0, std::vector<uint8_t>(16)}).empty());
    EXPECT_TRUE(session.on_message(CloseChannelMsg{2}).empty());
    // A name that is not a channel name at all.
    EXPECT_EQ(error_codes(session.on_message(OpenChannelMsg{3, "scene.bin", 16})),
              std::vector<ErrorCode>{ErrorCode::kUnknownChannel});
    // A write to a channel id never opened breaks the protocol.
    ServerActions stray = session.on_message(WriteChannelMsg{9, 0, {1, 2, 3}});
    EXPECT_EQ(error_codes(stray), std::vector<ErrorCode>{ErrorCode::kUnknownChannel});
    EXPECT_TRUE(closes(stray));
}

TEST(ServerSession, OversizedChannelIsRefusedAndTheConnectionStays) {
    ServerSession session({});
    hello(session);
    const uint64_t limit = 4 + uint64_t{kMaxSceneLights} * scene_record_bytes();
    ServerActions oversized = session.on_message(OpenChannelMsg{kChannel, scene_channel_name(kSceneGuid), limit + 1});
    EXPECT_EQ(error_codes(oversized), std::vector<ErrorCode>{ErrorCode::kTooLarge});
    EXPECT_FALSE(closes(oversized));

    // More bytes than announced: the scene is invalid, the connection stays.
    ServerActions opened = session.on_message(OpenChannelMsg{2, scene_channel_name(kSceneGuid), 4});
    EXPECT_TRUE(opened.empty());
    ServerActions longer = session.on_message(WriteChannelMsg{2, 0, std::vector<uint8_t>(8)});
    EXPECT_EQ(error_codes(longer), std::vector<ErrorCode>{ErrorCode::kInvalidScene});
    EXPECT_FALSE(closes(longer));
    EXPECT_TRUE(session.idle());
}

TEST(ServerSession, TooManyOpenChannelsIsBusy) {
    ServerSession session({});
    hello(session);
    for (uint32_t id = 1; id <= kMaxOpenChannels; ++id)
        EXPECT_TRUE(session.on_message(OpenChannelMsg{id, scene_channel_name(kSceneGuid), 100}).empty());
    ServerActions busy = session.on_message(OpenChannelMsg{99, scene_channel_name(kSceneGuid), 100});
    EXPECT_EQ(error_codes(busy), std::vector<ErrorCode>{ErrorCode::kBusy});
}

TEST(ServerSession, FullServerAnswersHelloBusy) {
    ServerSessionOptions options;
    options.busy_reason = "256 connections open";
    ServerSession session(options);
    ServerActions actions = hello(session);
    EXPECT_EQ(error_codes(actions), std::vector<ErrorCode>{ErrorCode::kBusy});
    EXPECT_TRUE(closes(actions));
}

TEST(ServerSession, ChannelsBeyondTheMemoryBudgetAreBusy) {
    const std::vector<SceneLight> lights = scene_lights();
    const uint64_t scene_bytes = encode_scene_channel(lights).size();
    // Room for the scene channel and its bake's estimated peak, not for another channel that size.
    const uint64_t bake_bytes =
        kBakeFixedBytes + lights.size() * (kTreeBytesPerLight + kExactPairingBytesPerNode);
    MemoryBudget budget(scene_bytes + bake_bytes);
    ServerSessionOptions options;
    options.memory_budget = &budget;
    {
        ServerSession session(options);
        hello(session);
        open_and_write(session, lights);
        EXPECT_EQ(budget.used(), scene_bytes);
        // A second channel does not fit while the first is held: busy, and the connection stays.
        ServerActions busy =
            session.on_message(OpenChannelMsg{2, scene_channel_name(kSceneGuid), bake_bytes + 1});
        EXPECT_EQ(error_codes(busy), std::vector<ErrorCode>{ErrorCode::kBusy});
        EXPECT_FALSE(closes(busy));
        // The stored scene keeps its bytes; another session cannot take them either.
        session.on_message(CloseChannelMsg{kChannel});
        EXPECT_EQ(budget.used(), scene_bytes);
        ServerSession other(options);
        hello(other);
        EXPECT_EQ(
            error_codes(other.on_message(OpenChannelMsg{1, scene_channel_name(kSceneGuid), bake_bytes + 1})),
            std::vector<ErrorCode>{ErrorCode::kBusy});
        EXPECT_EQ(count_of<StartBake>(session.on_message(bake_request())), 1u);
    }
    EXPECT_EQ(budget.used(), 0u);  // a session gives its bytes back when it ends
}

TEST(ServerSession, SecondBakeWhileOneRunsIsBusy) {
    ServerSession session = session_with_scene();
    ServerActions first = session.on_message(bake_request(1));
    ASSERT_EQ(count_of<StartBake>(first), 1u);
    ServerActions second = session.on_message(bake_request(2));
    EXPECT_EQ(error_codes(second), std::vector<ErrorCode>{ErrorCode::kBusy});
    EXPECT_EQ(std::get<ErrorMsg>(sent(second)[0]).bake_id, 2u);
    EXPECT_EQ(count_of<StartBake>(second), 0u);
    EXPECT_TRUE(session.bake_running());

    // The first bake goes on; once delivered, a new one is accepted.
    ServerActions finished = session.on_bake_finished(1, built_tree());
    ASSERT_EQ(count_of<StreamResult>(finished), 1u);
    EXPECT_EQ(error_codes(session.on_message(bake_request(3))), std::vector<ErrorCode>{ErrorCode::kBusy});
    session.on_result_delivered();
    EXPECT_TRUE(session.idle());
    EXPECT_EQ(count_of<StartBake>(session.on_message(bake_request(3))), 1u);
}

TEST(ServerSession, ResultIsStreamedWithBakeDone) {
    ServerSession session = session_with_scene();
    ServerActions queued = session.on_message(bake_request());
    ASSERT_EQ(sent(queued).size(), 1u);
    EXPECT_EQ(std::get<ProgressMsg>(sent(queued)[0]).stage, "queued");

    ServerActions progress = session.on_bake_progress(ProgressMsg{kBake, "level 1", 50.0f});
    ASSERT_EQ(sent(progress).size(), 1u);
    EXPECT_TRUE(session.on_bake_progress(ProgressMsg{kBake + 1, "stale", 1.0f}).empty());

    Result<BuildResult> built = built_tree();
    ASSERT_TRUE(built);
    const size_t nodes = built->tree.nodes.size();
    ServerActions finished = session.on_bake_finished(kBake, std::move(built));
    const StreamResult* stream = first_of<StreamResult>(finished);
    ASSERT_NE(stream, nullptr);
    EXPECT_EQ(stream->done.bake_id, kBake);
    EXPECT_EQ(stream->done.node_count, nodes);
    EXPECT_EQ(stream->tree->nodes.size(), nodes);
    EXPECT_GE(stream->channel_id, 1u << 31);  // server-opened channels use the upper half
    EXPECT_TRUE(session.streaming());
    EXPECT_FALSE(session.idle());
    session.on_result_delivered();
    EXPECT_TRUE(session.idle());
}

TEST(ServerSession, FailedBuildIsBakeFailed) {
    ServerSession session = session_with_scene();
    session.on_message(bake_request());
    ServerActions failed = session.on_bake_finished(kBake, make_error("no memory"));
    EXPECT_EQ(error_codes(failed), std::vector<ErrorCode>{ErrorCode::kBakeFailed});
    EXPECT_TRUE(session.idle());
}

TEST(ServerSession, CancelBeforeTheChannelClosesIsIgnored) {
    ServerSession session({});
    hello(session);
    open_and_write(session, scene_lights());
    EXPECT_TRUE(session.on_message(CancelMsg{kBake}).empty());
    session.on_message(CloseChannelMsg{kChannel});
    EXPECT_EQ(count_of<StartBake>(session.on_message(bake_request())), 1u);
}

TEST(ServerSession, CancelWhileQueued) {
    ServerSession session = session_with_scene();
    session.on_message(bake_request());
    ServerActions cancel = session.on_message(CancelMsg{kBake});
    ASSERT_EQ(count_of<CancelBake>(cancel), 1u);
    EXPECT_EQ(first_of<CancelBake>(cancel)->bake_id, kBake);
    EXPECT_TRUE(session.on_message(CancelMsg{kBake}).empty());  // asked once
    // The worker sees the flag before it starts.
    ServerActions finished =
        session.on_bake_finished(kBake, make_error("cancelled before start", ErrorKind::kCancelled));
    EXPECT_EQ(error_codes(finished), std::vector<ErrorCode>{ErrorCode::kCancelled});
    EXPECT_TRUE(session.idle());
}

TEST(ServerSession, CancelWhileBuilding) {
    ServerSession session = session_with_scene();
    session.on_message(bake_request());
    session.on_bake_progress(ProgressMsg{kBake, "level 0", 10.0f});
    EXPECT_EQ(count_of<CancelBake>(session.on_message(CancelMsg{kBake})), 1u);
    // However the build ends once cancel was asked, the outcome is the cancel's code.
    ServerActions finished = session.on_bake_finished(kBake, make_error("interrupted"));
    EXPECT_EQ(error_codes(finished), std::vector<ErrorCode>{ErrorCode::kCancelled});
    EXPECT_EQ(count_of<StreamResult>(finished), 0u);
}

TEST(ServerSession, CancelWhileStreamingStopsTheStream) {
    ServerSession session = session_with_scene();
    session.on_message(bake_request());
    ASSERT_EQ(count_of<StreamResult>(session.on_bake_finished(kBake, built_tree())), 1u);
    ServerActions cancel = session.on_message(CancelMsg{kBake});
    EXPECT_EQ(count_of<StopStream>(cancel), 1u);
    EXPECT_EQ(count_of<CancelBake>(cancel), 0u);  // nothing left to build
    EXPECT_EQ(error_codes(cancel), std::vector<ErrorCode>{ErrorCode::kCancelled});
    EXPECT_TRUE(session.idle());
}

TEST(ServerSession, CancelOfAnotherBakeIsIgnored) {
    ServerSession session = session_with_scene();
    session.on_message(bake_request());
    EXPECT_TRUE(session.on_message(CancelMsg{kBake + 1}).empty());
    EXPECT_EQ(count_of<StreamResult>(session.on_bake_finished(kBake, built_tree())), 1u);
}

TEST(ServerSession, ClosingCancelsTheBuildAndAnswersNothingMore) {
    ServerSession session = session_with_scene();
    session.on_message(bake_request());
    ServerActions closing = session.on_closing();
    EXPECT_EQ(count_of<CancelBake>(closing), 1u);
    EXPECT_TRUE(session.on_bake_progress(ProgressMsg{kBake, "level 0", 10.0f}).empty());
    EXPECT_TRUE(session.on_bake_finished(kBake, built_tree()).empty());
}

TEST(ServerSession, BadFramesCloseWithTheirCodes) {
    ServerSession malformed({});
    ServerActions a = malformed.on_malformed_frame("verifier failed");
    EXPECT_EQ(error_codes(a), std::vector<ErrorCode>{ErrorCode::kMalformedFrame});
    EXPECT_TRUE(closes(a));
    ServerSession oversized({});
    ServerActions b = oversized.on_bad_frame_header("frame of 20000000 bytes");
    EXPECT_EQ(error_codes(b), std::vector<ErrorCode>{ErrorCode::kTooLarge});
    EXPECT_TRUE(closes(b));
}

TEST(ServerSession, ClientMayNotSendServerMessages) {
    ServerSession session({});
    hello(session);
    ServerActions actions = session.on_message(BakeDoneMsg{});
    EXPECT_EQ(error_codes(actions), std::vector<ErrorCode>{ErrorCode::kMalformedFrame});
    EXPECT_TRUE(closes(actions));
}

TEST(ServerSession, StatusIsAnsweredAfterHelloOnlyAndClientsMayNotSendReplies) {
    ServerSessionOptions options;
    options.token = "secret";
    options.status = [] {
        StatusReplyMsg reply;
        reply.version = "lightmass_server 9.9.9";
        reply.memory_budget_bytes = 4096;
        reply.mpi_max_ranks = 16;
        return reply;
    };
    ServerSession before(options);
    ServerActions refused = before.on_message(StatusRequestMsg{3});
    EXPECT_EQ(error_codes(refused), std::vector<ErrorCode>{ErrorCode::kMalformedFrame});
    EXPECT_TRUE(closes(refused));

    ServerSession wrong_token(options);
    EXPECT_EQ(error_codes(hello(wrong_token, "wrong")), std::vector<ErrorCode>{ErrorCode::kAuthentication});
    EXPECT_TRUE(wrong_token.on_message(StatusRequestMsg{3}).empty()) << "a refused client got an answer";

    ServerSession session(options);
    hello(session, "secret");
    ServerActions answered = session.on_message(StatusRequestMsg{3});
    const std::vector<Message> messages = sent(answered);
    ASSERT_EQ(messages.size(), 1u);
    const auto& reply = std::get<StatusReplyMsg>(messages[0]);
    EXPECT_EQ(reply.request_id, 3u);
    EXPECT_EQ(reply.version, "lightmass_server 9.9.9");
    EXPECT_EQ(reply.memory_budget_bytes, 4096u);
    EXPECT_FALSE(closes(answered));

    ServerActions reply_from_client = session.on_message(StatusReplyMsg{});
    EXPECT_EQ(error_codes(reply_from_client), std::vector<ErrorCode>{ErrorCode::kMalformedFrame});
}

TEST(ServerSession, TheBakesStatusIsQueuedThenRunningThenStreaming) {
    ServerSessionOptions options;
    options.connection_id = 12;
    ServerSession session = session_with_scene(options);
    EXPECT_FALSE(session.bake_status().has_value());
    BakeRequestMsg request = bake_request();
    request.ranks = 3;
    session.on_message(request);
    std::optional<BakeStatusEntry> queued = session.bake_status();
    ASSERT_TRUE(queued.has_value());
    EXPECT_EQ(queued->connection, 12u);
    EXPECT_EQ(queued->bake_id, kBake);
    EXPECT_EQ(queued->state, "queued");
    EXPECT_EQ(queued->ranks, 3u);

    session.on_bake_progress(ProgressMsg{kBake, "level 4", 37.5f});
    std::optional<BakeStatusEntry> running = session.bake_status();
    ASSERT_TRUE(running.has_value());
    EXPECT_EQ(running->state, "running");
    EXPECT_EQ(running->stage, "level 4");
    EXPECT_EQ(running->percent, 37.5f);

    session.on_bake_finished(kBake, built_tree());
    EXPECT_EQ(session.bake_status()->state, "streaming");
    session.on_result_delivered();
    EXPECT_FALSE(session.bake_status().has_value());
}

TEST(ServerSession, RecordsTheSceneAndTheResultWhenAsked) {
    ServerSessionOptions options;
    options.record_channels = true;
    ServerSession session({options});
    hello(session);
    const std::vector<SceneLight> lights = scene_lights();
    open_and_write(session, lights);
    ServerActions closed = session.on_message(CloseChannelMsg{kChannel});
    const RecordChannel* scene = first_of<RecordChannel>(closed);
    ASSERT_NE(scene, nullptr);
    EXPECT_EQ(scene->name, scene_channel_name(kSceneGuid));
    EXPECT_EQ(scene->bytes, encode_scene_channel(lights));

    session.on_message(bake_request());
    ServerActions finished = session.on_bake_finished(kBake, built_tree());
    const RecordChannel* result = first_of<RecordChannel>(finished);
    ASSERT_NE(result, nullptr);
    EXPECT_EQ(result->name, lightcuts_result_channel_name());
}

// An emissive triangle and a degenerate one.
SceneGeometry emissive_geometry(float emission) {
    SceneGeometry g;
    SurfaceMaterial panel;
    panel.emission = glm::vec3(emission);
    g.materials = {panel};
    SurfaceTriangle t;
    t.positions[0] = {0, 2, 0};
    t.positions[1] = {1, 2, 1};
    t.positions[2] = {1, 2, 0};
    t.normals[0] = t.normals[1] = t.normals[2] = {0, -1, 0};
    SurfaceTriangle line = t;
    line.positions[2] = line.positions[1];
    g.triangles = {t, line};
    return g;
}

ServerActions send_geometry(ServerSession& session, const SceneGeometry& geometry) {
    constexpr uint32_t kGeometryChannel = 2;
    const std::vector<uint8_t> bytes = encode_geometry_channel(geometry);
    const std::string name = geometry_channel_name(kSceneGuid);
    ServerActions all = session.on_message(OpenChannelMsg{kGeometryChannel, name, bytes.size()});
    for (ServerActions more : {session.on_message(WriteChannelMsg{kGeometryChannel, 0, bytes}),
                               session.on_message(CloseChannelMsg{kGeometryChannel})})
        all.insert(all.end(), more.begin(), more.end());
    return all;
}

size_t warnings(const ServerActions& actions) {
    size_t n = 0;
    for (const Message& message : sent(actions)) n += std::holds_alternative<WarningMsg>(message) ? 1 : 0;
    return n;
}

TEST(ServerSession, GeometryChannelReachesTheBakeWithItsBudget) {
    ServerSession session = session_with_scene();
    ServerActions received = send_geometry(session, emissive_geometry(3.0f));
    EXPECT_TRUE(error_codes(received).empty());
    EXPECT_EQ(warnings(received), 1u);  // the degenerate triangle, skipped and counted
    BakeRequestMsg request = bake_request();
    request.geometry_channel = geometry_channel_name(kSceneGuid);
    request.area_lights = 500;
    ServerActions started = session.on_message(request);
    EXPECT_TRUE(error_codes(started).empty());
    const StartBake* start = first_of<StartBake>(started);
    ASSERT_NE(start, nullptr);
    ASSERT_NE(start->inputs.geometry, nullptr);
    EXPECT_EQ(start->inputs.geometry->triangles.size(), 1u);
    EXPECT_EQ(start->inputs.area_lights, 500u);
}

TEST(ServerSession, WithoutGeometryTheBakeHasNoneAndTheDefaultBudget) {
    ServerSession session = session_with_scene();
    ServerActions started = session.on_message(bake_request());
    const StartBake* start = first_of<StartBake>(started);
    ASSERT_NE(start, nullptr);
    EXPECT_EQ(start->inputs.geometry, nullptr);
    EXPECT_EQ(start->inputs.area_lights, kDefaultAreaLights);
}

TEST(ServerSession, BadGeometryOrBudgetIsRefusedAndNothingBakes) {
    ServerSession session = session_with_scene();
    // Negative emission: the channel is refused as it streams in.
    EXPECT_EQ(error_codes(send_geometry(session, emissive_geometry(-1.0f))),
              std::vector<ErrorCode>{ErrorCode::kInvalidScene});
    BakeRequestMsg request = bake_request();
    request.geometry_channel = geometry_channel_name(kSceneGuid);
    ServerActions refused = session.on_message(request);
    EXPECT_EQ(error_codes(refused), std::vector<ErrorCode>{ErrorCode::kUnknownChannel});
    EXPECT_EQ(count_of<StartBake>(refused), 0u);
    // An absurd budget.
    EXPECT_TRUE(error_codes(send_geometry(session, emissive_geometry(1.0f))).empty());
    request.area_lights = kMaxAreaLights + 1;
    refused = session.on_message(request);
    EXPECT_EQ(error_codes(refused), std::vector<ErrorCode>{ErrorCode::kInvalidScene});
    EXPECT_EQ(count_of<StartBake>(refused), 0u);
}

TEST(ServerSession, DegenerateGeometryOnlyWarnsAndBakes) {
    ServerSession session = session_with_scene();
    SceneGeometry degenerate = emissive_geometry(1.0f);
    degenerate.triangles.erase(degenerate.triangles.begin());
    ServerActions received = send_geometry(session, degenerate);
    EXPECT_TRUE(error_codes(received).empty());
    EXPECT_EQ(warnings(received), 1u);
    BakeRequestMsg request = bake_request();
    request.geometry_channel = geometry_channel_name(kSceneGuid);
    ServerActions started = session.on_message(request);
    const StartBake* start = first_of<StartBake>(started);
    ASSERT_NE(start, nullptr);
    ASSERT_NE(start->inputs.geometry, nullptr);
    EXPECT_TRUE(start->inputs.geometry->triangles.empty());
}

// Issue 27: a request's settings are checked when it arrives, before it is queued.
TEST(ServerSession, SettingsOutOfRangeAreRefusedOnArrival) {
    ServerSession session = session_with_scene();
    std::vector<BakeRequestMsg> bad(6, bake_request());
    bad[0].indirect = {IndirectMethod::kVpl, 0, 1000, 0.25f, 0.01f};  // no bounce
    bad[1].indirect = {IndirectMethod::kVpl, kMaxBakeBounces + 1, 1000, 0.25f,
                       0.01f};                                                    // deeper than recorded
    bad[2].indirect = {IndirectMethod::kVpl, 1, kMaxVplPaths + 1, 0.25f, 0.01f};  // 10^12 paths and the like
    bad[3].indirect = {IndirectMethod::kRadiosity, 1, 1000, 1e-37f, 0.01f};
    bad[4].indirect = {IndirectMethod::kRadiosity, 1, 1000, 0.25f, 1.0f};
    bad[5].area_lights = kMaxAreaLights + 1;
    for (const BakeRequestMsg& request : bad) {
        ServerActions refused = session.on_message(request);
        EXPECT_EQ(error_codes(refused), std::vector<ErrorCode>{ErrorCode::kInvalidScene});
        EXPECT_EQ(count_of<StartBake>(refused), 0u);
        EXPECT_FALSE(closes(refused));
    }
    // The numbers read as numbers: 1e-37, not 0.000000.
    const std::string text = std::get<ErrorMsg>(sent(session.on_message(bad[3]))[0]).text;
    EXPECT_NE(text.find("patch size 1e-37"), std::string::npos) << text;
    EXPECT_FALSE(session.bake_running());
}

TEST(ServerSession, RadiosityPatchesBeyondTheLimitAreTooLargeOnArrival) {
    ServerSession session = session_with_scene();
    EXPECT_TRUE(error_codes(send_geometry(session, emissive_geometry(1.0f))).empty());
    BakeRequestMsg request = bake_request();
    request.geometry_channel = geometry_channel_name(kSceneGuid);
    request.indirect = {IndirectMethod::kRadiosity, 1, 1000, 1e-4f, 0.01f};  // 200 million patches
    ServerActions refused = session.on_message(request);
    EXPECT_EQ(error_codes(refused), std::vector<ErrorCode>{ErrorCode::kTooLarge});
    EXPECT_EQ(count_of<StartBake>(refused), 0u);
}

TEST(ServerSession, ABakeBeyondTheBudgetIsTooLargeAndOneThatDoesNotFitNowIsBusy) {
    MemoryBudget budget(uint64_t{64} << 20);
    ServerSessionOptions options;
    options.memory_budget = &budget;
    ServerSession session = session_with_scene(options);
    EXPECT_TRUE(error_codes(send_geometry(session, emissive_geometry(1.0f))).empty());
    // 4,194,304 area-light samples need gigabytes: refused up front, whatever is free.
    BakeRequestMsg request = bake_request();
    request.geometry_channel = geometry_channel_name(kSceneGuid);
    request.area_lights = kMaxAreaLights;
    ServerActions refused = session.on_message(request);
    ASSERT_EQ(error_codes(refused), std::vector<ErrorCode>{ErrorCode::kTooLarge});
    const std::string text = std::get<ErrorMsg>(sent(refused)[0]).text;
    EXPECT_NE(text.find("the budget is 64 MB"), std::string::npos) << text;
    EXPECT_NE(text.find("needs 2,"), std::string::npos) << text;  // 4.2 M lights x 600 bytes

    // 40,000 samples (61 MB) fit once; a second session's while the first runs does not.
    request.area_lights = 40000;
    const uint64_t held = budget.used();
    ServerActions first = session.on_message(request);
    ASSERT_EQ(count_of<StartBake>(first), 1u);
    const uint64_t reserved = budget.used() - held;
    EXPECT_GE(reserved, 40000 * kTreeBytesPerLight);
    ServerSession other = session_with_scene(options);
    EXPECT_TRUE(error_codes(send_geometry(other, emissive_geometry(1.0f))).empty());
    EXPECT_EQ(error_codes(other.on_message(request)), std::vector<ErrorCode>{ErrorCode::kBusy});
    // The first bake ends (here cancelled): its bytes are free again, and the other bake fits.
    const uint64_t before = budget.used();
    session.on_bake_finished(kBake, make_error("cancelled", ErrorKind::kCancelled));
    EXPECT_EQ(budget.used(), before - reserved);
    EXPECT_EQ(count_of<StartBake>(other.on_message(request)), 1u);
}

TEST(ServerSession, VplBakesCarryTheirLightCapAndSmallBakesTheSmallLane) {
    ServerSession session = session_with_scene();
    EXPECT_TRUE(error_codes(send_geometry(session, emissive_geometry(1.0f))).empty());
    ServerActions small = session.on_message(bake_request(1));
    ASSERT_NE(first_of<StartBake>(small), nullptr);
    EXPECT_TRUE(first_of<StartBake>(small)->small);
    session.on_bake_finished(1, make_error("cancelled", ErrorKind::kCancelled));

    BakeRequestMsg request = bake_request(2);
    request.geometry_channel = geometry_channel_name(kSceneGuid);
    request.indirect = {IndirectMethod::kVpl, 65535, 1000, 0.25f, 0.01f};
    ServerActions deep = session.on_message(request);
    const StartBake* start = first_of<StartBake>(deep);
    ASSERT_NE(start, nullptr);
    EXPECT_FALSE(start->small);
    // The roulette's paths at albedo 1 (vpl_light_reservation): 40 lights each, not 65,535.
    EXPECT_EQ(start->inputs.indirect.vpl.max_lights, 40000u);
    session.on_bake_finished(2, make_error("cancelled", ErrorKind::kCancelled));

    request.bake_id = 3;
    request.indirect = {IndirectMethod::kVpl, 2, 1000, 0.25f, 0.01f};
    const ServerActions shallow = session.on_message(request);  // `start` points into it
    start = first_of<StartBake>(shallow);
    ASSERT_NE(start, nullptr);
    EXPECT_EQ(start->inputs.indirect.vpl.max_lights, 2000u);
}

// A bake over MPI ranks waits on its job for its whole length, so it never takes
// the small lane; its estimated peak is reserved like a bake in the process.
TEST(ServerSession, ABakeOverRanksTakesTheBigPoolAndReservesItsFootprint) {
    MemoryBudget budget(uint64_t{64} << 20);
    ServerSessionOptions options;
    options.memory_budget = &budget;
    ServerSession session = session_with_scene(options);
    BakeRequestMsg request = bake_request(1);
    request.ranks = 2;
    const uint64_t held = budget.used();
    const ServerActions actions = session.on_message(request);  // `start` points into it
    const StartBake* start = first_of<StartBake>(actions);
    ASSERT_NE(start, nullptr);
    EXPECT_EQ(start->inputs.ranks, 2u);
    EXPECT_FALSE(start->small);
    EXPECT_GT(budget.used(), held);
    session.on_bake_finished(1, make_error("cancelled", ErrorKind::kCancelled));
    EXPECT_EQ(budget.used(), held);
}

TEST(ServerSession, OpenChannelsAreCappedPerConnectionAndFreedOnClose) {
    MemoryBudget budget(uint64_t{1} << 30);
    ServerSessionOptions options;
    options.memory_budget = &budget;
    options.max_connection_channel_bytes = 1000;
    ServerSession session(options);
    hello(session);
    EXPECT_TRUE(session.on_message(OpenChannelMsg{1, scene_channel_name(kSceneGuid), 600}).empty());
    EXPECT_TRUE(session.receiving_channel());
    ServerActions over = session.on_message(OpenChannelMsg{2, scene_channel_name(kSceneGuid), 401});
    EXPECT_EQ(error_codes(over), std::vector<ErrorCode>{ErrorCode::kBusy});
    EXPECT_FALSE(closes(over));
    EXPECT_TRUE(session.on_message(OpenChannelMsg{3, scene_channel_name(kSceneGuid), 400}).empty());
    EXPECT_EQ(budget.used(), 1000u);
    // A peer that goes silent is closed by its deadline: the half-received channels' bytes come back at once.
    session.on_closing();
    EXPECT_EQ(budget.used(), 0u);
}

}  // namespace
}  // namespace lc::bake
