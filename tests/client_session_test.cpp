// The bake client's protocol state machine with no socket: what it sends is
// pulled with next_message(), the server's answers are pushed in, and what it
// asks of the I/O layer comes out as ClientActions (client_action.h), checked
// here as ServerSession's are; the dump tests apply them with ClientOutputs,
// as bake_client.cpp does. Outcomes are checked by their ErrorKind, never their text.
#include <gtest/gtest.h>

#include <algorithm>

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "editor_client/bake/client_outputs.h"
#include "editor_client/bake/client_session.h"
#include "lightmass_server/net/result_stream.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/codec.h"
#include "protocol/dump.h"
#include "protocol/environment_records.h"
#include "protocol/frame_decoder.h"
#include "protocol/geometry_channel.h"
#include "test_paths.h"
#include "tree_invariants.h"

namespace lc::client {
namespace {

constexpr Guid kSceneGuid{0x11111111u, 0x22222222u, 0x33333333u, 0x44444444u};
constexpr uint32_t kBake = 5;

std::vector<SceneLight> scene_lights() { return test::random_lights(40, 9, LightType::kPoint); }

ClientSessionOptions session_options() {
    ClientSessionOptions options;
    options.token = "secret";
    options.request.bake_id = kBake;
    options.request.seed = 17;
    options.chunk_bytes = 256;  // several WriteChannel messages for 40 lights
    return options;
}

std::vector<Message> drain(ClientSession& session) {
    std::vector<Message> messages;
    while (std::optional<Message> message = session.next_message()) messages.push_back(std::move(*message));
    return messages;
}

// A session whose Hello was answered and whose upload and BakeRequest were sent.
void upload(ClientSession& session) {
    session.start();
    ASSERT_EQ(drain(session).size(), 1u);
    session.on_message(HelloAckMsg{kProtocolVersion, "server"});
    std::vector<Message> upload = drain(session);
    ASSERT_FALSE(upload.empty());
    ASSERT_TRUE(std::holds_alternative<BakeRequestMsg>(upload.back()));
    ASSERT_EQ(session.stage(), ClientSession::Stage::kBaking);
}

// The I/O layer's part without a socket: the session's actions applied after
// each call, a failure handed back to the session, as bake_client.cpp does.
void apply_actions(ClientSession& session, ClientOutputs& outputs) {
    Status applied = outputs.apply(session.take_actions());
    if (applied) return;
    session.fail_outputs(applied.failure());
    ASSERT_TRUE(outputs.apply(session.take_actions()));
}

void deliver(ClientSession& session, ClientOutputs& outputs, const Message& message) {
    session.on_message(message);
    apply_actions(session, outputs);
}

template <typename A>
std::vector<A> actions_of(const ClientActions& actions) {
    std::vector<A> matching;
    for (const ClientAction& action : actions)
        if (const A* a = std::get_if<A>(&action)) matching.push_back(*a);
    return matching;
}

// What a server sends for a finished bake of `lights`: the result channel and BakeDone.
std::vector<Message> result_messages(const std::vector<SceneLight>& lights) {
    Result<bake::BuildResult> built = bake::build_light_tree(lights, bake::BuildOptions{}, nullptr);
    EXPECT_TRUE(built);
    auto tree = std::make_shared<const LightTree>(std::move(built->tree));
    BakeDoneMsg done;
    done.bake_id = kBake;
    done.result_channel = lightcuts_result_channel_name();
    done.node_count = static_cast<uint32_t>(tree->nodes.size());
    done.leaf_count = tree->leaf_count;
    bake::ResultStream stream(tree, 1u << 31, done, 512);
    std::vector<Message> messages;
    while (auto frame = stream.next_frame()) {
        Result<Message> message = decode_message(frame->bytes().subspan(kFrameHeaderBytes));
        EXPECT_TRUE(message) << message.error();
        messages.push_back(std::move(message.value()));
    }
    return messages;
}

TEST(ClientSession, SendsHelloThenTheSceneChannelThenTheRequest) {
    const std::vector<SceneLight> lights = scene_lights();
    ClientSession session(lights, kSceneGuid, session_options());
    EXPECT_FALSE(session.next_message());  // nothing before the connection is up
    session.start();
    std::vector<Message> hello = drain(session);
    ASSERT_EQ(hello.size(), 1u);
    EXPECT_EQ(std::get<HelloMsg>(hello[0]).token, "secret");
    EXPECT_EQ(std::get<HelloMsg>(hello[0]).protocol_version, kProtocolVersion);
    EXPECT_EQ(session.stage(), ClientSession::Stage::kAwaitingHelloAck);
    EXPECT_FALSE(session.next_message());  // the upload waits for HelloAck

    session.on_message(HelloAckMsg{kProtocolVersion, "server"});
    std::vector<Message> upload = drain(session);
    ASSERT_GE(upload.size(), 5u);
    const std::vector<uint8_t> expected = encode_scene_channel(lights);
    const auto& open = std::get<OpenChannelMsg>(upload.front());
    EXPECT_EQ(open.name, scene_channel_name(kSceneGuid));
    EXPECT_EQ(open.total_bytes, expected.size());
    std::vector<uint8_t> written;
    for (size_t i = 1; i + 2 < upload.size(); ++i) {
        const auto& write = std::get<WriteChannelMsg>(upload[i]);
        EXPECT_EQ(write.channel_id, open.channel_id);
        EXPECT_EQ(write.offset, written.size());
        EXPECT_LE(write.data.size(), 256u);
        written.insert(written.end(), write.data.begin(), write.data.end());
    }
    EXPECT_EQ(written, expected);
    EXPECT_EQ(std::get<CloseChannelMsg>(upload[upload.size() - 2]).channel_id, open.channel_id);
    const auto& request = std::get<BakeRequestMsg>(upload.back());
    EXPECT_EQ(request.bake_id, kBake);
    EXPECT_EQ(request.scene_channel, open.name);
    EXPECT_EQ(request.seed, 17u);
    EXPECT_TRUE(request.environment_channel.empty());  // no environment: nothing new on the wire
    EXPECT_EQ(session.stage(), ClientSession::Stage::kBaking);
}

TEST(ClientSession, SendsTheEnvironmentChannelAfterTheSceneAndNamesIt) {
    auto environment = std::make_shared<Environment>();
    environment->map = EquirectMap{16, 8, std::vector<glm::vec3>(128, glm::vec3(0.25f))};
    ClientSessionOptions options = session_options();
    options.environment = environment;
    options.request.environment_lights = 77;
    ClientSession session(scene_lights(), kSceneGuid, options);
    session.start();
    drain(session);
    session.on_message(HelloAckMsg{kProtocolVersion, "server"});
    std::vector<Message> upload = drain(session);
    std::vector<std::string> opened;
    std::vector<uint8_t> environment_bytes;
    for (const Message& message : upload) {
        if (auto* open = std::get_if<OpenChannelMsg>(&message)) opened.push_back(open->name);
        if (auto* write = std::get_if<WriteChannelMsg>(&message); write && opened.size() == 2)
            environment_bytes.insert(environment_bytes.end(), write->data.begin(), write->data.end());
    }
    ASSERT_EQ(opened.size(), 2u);
    EXPECT_EQ(opened[0], scene_channel_name(kSceneGuid));
    EXPECT_EQ(opened[1], environment_channel_name(kSceneGuid));
    EXPECT_EQ(environment_bytes, encode_environment_channel(*environment));
    const auto& request = std::get<BakeRequestMsg>(upload.back());
    EXPECT_EQ(request.environment_channel, opened[1]);
    EXPECT_EQ(request.environment_lights, 77u);
}

TEST(ClientSession, ReceivesProgressWarningsAndTheTree) {
    const std::vector<SceneLight> lights = scene_lights();
    ClientSession session(lights, kSceneGuid, session_options());
    upload(session);
    EXPECT_TRUE(session.take_actions().empty()) << "nothing to record or show during the upload";

    std::vector<std::string> stages;
    std::vector<std::string> warnings;
    const auto collect = [&] {
        for (const ClientAction& action : session.take_actions()) {
            if (auto* p = std::get_if<client_action::ReportProgress>(&action)) stages.push_back(p->progress.stage);
            else if (auto* w = std::get_if<client_action::ReportWarning>(&action)) warnings.push_back(w->text);
            else ADD_FAILURE() << "only progress and warnings without --record or a dump, got action "
                               << action.index();
        }
    };
    session.on_message(ProgressMsg{kBake, "queued", 0.0f});
    collect();
    session.on_message(WarningMsg{kBake, "2 classic lights left out"});
    collect();
    for (const Message& message : result_messages(lights)) {
        ASSERT_FALSE(session.finished());
        session.on_message(message);
        collect();
    }
    ASSERT_TRUE(session.finished());
    EXPECT_TRUE(session.succeeded());
    Result<BakeOutcome> outcome = session.take_result();
    ASSERT_TRUE(outcome) << outcome.error();
    EXPECT_EQ(outcome->tree.nodes.size(), 2 * lights.size() - 1);
    EXPECT_EQ(outcome->result_channel_name, lightcuts_result_channel_name());
    EXPECT_EQ(outcome->warnings, std::vector<std::string>{"2 classic lights left out"});
    EXPECT_EQ(warnings, outcome->warnings);
    ASSERT_GE(stages.size(), 2u);
    EXPECT_EQ(stages.front(), "queued");
    EXPECT_EQ(stages.back(), "receiving");
}

// The raw channel is kept for a dump only; without one the tree alone comes
// back, decoded as the chunks arrived, and it is the same tree.
TEST(ClientSession, KeepsTheRawResultChannelOnlyWhenAsked) {
    const std::vector<SceneLight> lights = scene_lights();
    std::vector<BakeOutcome> outcomes;
    for (bool keep : {true, false}) {
        ClientSessionOptions options = session_options();
        options.keep_result_channel = keep;
        ClientSession session(lights, kSceneGuid, options);
        upload(session);
        for (const Message& message : result_messages(lights)) session.on_message(message);
        Result<BakeOutcome> outcome = session.take_result();
        ASSERT_TRUE(outcome) << outcome.error();
        outcomes.push_back(std::move(outcome.value()));
    }
    EXPECT_FALSE(outcomes[0].result_channel.empty());
    EXPECT_TRUE(outcomes[1].result_channel.empty());
    ASSERT_EQ(outcomes[0].tree.nodes.size(), outcomes[1].tree.nodes.size());
    EXPECT_EQ(encode_result_channel(outcomes[1].tree), encode_result_channel(outcomes[0].tree));
}

// bake: the tree is validated as it arrives and never decoded into nodes;
// the dump holds the same channel, and a bad record still fails the bake.
TEST(ClientSession, ValidatesWithoutDecodingTheTreeWhenAsked) {
    const std::vector<SceneLight> lights = scene_lights();
    const std::filesystem::path dir = test::make_temp_dir("client-session-validate-only");
    const std::vector<Message> result = result_messages(lights);
    ClientSessionOptions options = session_options();
    options.keep_result_channel = false;
    options.decode_tree = false;
    options.write_dump = true;
    ClientOutputs outputs({.result_dump = dir / "tree.lcut"});
    ClientSession session(lights, kSceneGuid, options);
    upload(session);
    for (const Message& message : result) deliver(session, outputs, message);
    Result<BakeOutcome> outcome = session.take_result();
    ASSERT_TRUE(outcome) << outcome.error();
    EXPECT_TRUE(outcome->tree.nodes.empty());
    Result<ChannelDump> dump = read_dump(dir / "tree.lcut");
    ASSERT_TRUE(dump) << dump.error();
    Result<LightTree> tree = decode_result_channel(dump->payload);
    ASSERT_TRUE(tree) << tree.error();
    EXPECT_EQ(tree->nodes.size(), 2 * lights.size() - 1);

    std::vector<Message> corrupted = result;
    auto first_write = std::find_if(corrupted.begin(), corrupted.end(), [](const Message& m) {
        return std::holds_alternative<WriteChannelMsg>(m);
    });
    ASSERT_NE(first_write, corrupted.end());
    std::get<WriteChannelMsg>(*first_write).data.at(4 + 18) = 1;  // node 0's light_flags: an unknown bit
    ClientOutputs refused_outputs({.result_dump = dir / "refused.lcut"});
    ClientSession refusing(lights, kSceneGuid, options);
    upload(refusing);
    for (const Message& message : corrupted) {
        if (refusing.finished()) break;
        deliver(refusing, refused_outputs, message);
    }
    Result<BakeOutcome> refused = refusing.take_result();
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().find("node 0: FLightData.light_flags"), std::string::npos) << refused.error();
    EXPECT_FALSE(std::filesystem::exists(dir / "refused.lcut"));
}

// bake -o: the channel goes into the dump as it arrives, the dump appears
// once the tree is valid, and a bake cut short leaves no dump and no
// temporary file behind.
TEST(ClientSession, StreamsTheResultChannelIntoADump) {
    const std::vector<SceneLight> lights = scene_lights();
    const std::filesystem::path dir = test::make_temp_dir("client-session-dump");
    const std::vector<Message> result = result_messages(lights);
    ClientSessionOptions options = session_options();
    options.keep_result_channel = false;
    options.write_dump = true;
    const std::filesystem::path path = dir / "tree.lcut";
    ClientOutputs outputs({.result_dump = path});
    ClientSession session(lights, kSceneGuid, options);
    upload(session);
    for (const Message& message : result) {
        EXPECT_FALSE(std::filesystem::exists(path));
        deliver(session, outputs, message);
    }
    Result<BakeOutcome> outcome = session.take_result();
    ASSERT_TRUE(outcome) << outcome.error();
    EXPECT_TRUE(outcome->result_channel.empty());
    Result<ChannelDump> dump = read_dump(path);
    ASSERT_TRUE(dump) << dump.error();
    EXPECT_EQ(dump->channel_name, lightcuts_result_channel_name());
    EXPECT_EQ(dump->payload, encode_result_channel(outcome->tree));

    ClientSessionOptions cut_short = session_options();
    cut_short.write_dump = true;
    ClientOutputs cut_short_outputs({.result_dump = dir / "cut_short.lcut"});
    ClientSession cancelled(lights, kSceneGuid, cut_short);
    upload(cancelled);
    deliver(cancelled, cut_short_outputs, result[0]);  // OpenChannel
    deliver(cancelled, cut_short_outputs, result[1]);  // the first WriteChannel
    deliver(cancelled, cut_short_outputs, ErrorMsg{kBake, ErrorCode::kCancelled, "bake 5 cancelled during transfer"});
    EXPECT_EQ(cancelled.take_result().error_kind(), ErrorKind::kCancelled);
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator{}), 1);
    std::filesystem::remove_all(dir);
}

TEST(ClientSession, VersionMismatchIsRefused) {
    ClientSession session(scene_lights(), kSceneGuid, session_options());
    session.start();
    drain(session);
    Guid other = kProtocolVersion;
    other.d += 1;
    session.on_message(HelloAckMsg{other, "future server"});
    ASSERT_TRUE(session.finished());
    EXPECT_FALSE(session.next_message());  // nothing is uploaded
    EXPECT_EQ(session.take_result().error_kind(), ErrorKind::kRefused);
}

TEST(ClientSession, TokenRefusedByTheServer) {
    ClientSession session(scene_lights(), kSceneGuid, session_options());
    session.start();
    drain(session);
    session.on_message(ErrorMsg{0, ErrorCode::kAuthentication, "authentication failed"});
    EXPECT_EQ(session.take_result().error_kind(), ErrorKind::kRefused);
}

TEST(ClientSession, BusyServerIsBusy) {
    ClientSession session(scene_lights(), kSceneGuid, session_options());
    upload(session);
    session.on_message(ErrorMsg{kBake, ErrorCode::kBusy, "bake 1 is still running on this connection"});
    Result<BakeOutcome> outcome = session.take_result();
    EXPECT_EQ(outcome.error_kind(), ErrorKind::kBusy) << outcome.error();
}

TEST(ClientSession, FailedBakeIsAFailure) {
    ClientSession session(scene_lights(), kSceneGuid, session_options());
    upload(session);
    session.on_message(ErrorMsg{kBake, ErrorCode::kBakeFailed, "bake 5 failed"});
    EXPECT_EQ(session.take_result().error_kind(), ErrorKind::kFailed);
}

TEST(ClientSession, CancelBeforeBakeRequestEndsTheBakeAtOnce) {
    // Before connecting, while waiting for HelloAck, and in the middle of the upload.
    for (int stage = 0; stage < 3; ++stage) {
        ClientSession session(scene_lights(), kSceneGuid, session_options());
        if (stage >= 1) {
            session.start();
            drain(session);
        }
        if (stage == 2) {
            session.on_message(HelloAckMsg{kProtocolVersion, "server"});
            ASSERT_TRUE(session.next_message());  // OpenChannel
            ASSERT_TRUE(session.next_message());  // the first WriteChannel
        }
        session.cancel();
        ASSERT_TRUE(session.finished()) << stage;
        EXPECT_FALSE(session.next_message()) << stage;
        EXPECT_EQ(session.take_result().error_kind(), ErrorKind::kCancelled) << stage;
    }
}

TEST(ClientSession, CancelWhileBakingSendsCancelOnce) {
    ClientSession session(scene_lights(), kSceneGuid, session_options());
    upload(session);
    session.on_message(ProgressMsg{kBake, "level 0", 5.0f});
    session.cancel();
    session.cancel();
    std::vector<Message> sent = drain(session);
    ASSERT_EQ(sent.size(), 1u);
    EXPECT_EQ(std::get<CancelMsg>(sent[0]).bake_id, kBake);
    EXPECT_FALSE(session.finished());  // the server's answer ends it
    session.on_message(ErrorMsg{kBake, ErrorCode::kCancelled, "bake 5 cancelled"});
    EXPECT_EQ(session.take_result().error_kind(), ErrorKind::kCancelled);
}

TEST(ClientSession, CancelWhileReceivingTheResult) {
    const std::vector<SceneLight> lights = scene_lights();
    ClientSession session(lights, kSceneGuid, session_options());
    upload(session);
    std::vector<Message> result = result_messages(lights);
    session.on_message(result[0]);  // OpenChannel
    session.on_message(result[1]);  // the first WriteChannel
    session.cancel();
    std::vector<Message> sent = drain(session);
    ASSERT_EQ(sent.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<CancelMsg>(sent[0]));
    session.on_message(ErrorMsg{kBake, ErrorCode::kCancelled, "bake 5 cancelled during transfer"});
    EXPECT_EQ(session.take_result().error_kind(), ErrorKind::kCancelled);
}

TEST(ClientSession, UnknownResultChannelIsRejected) {
    ClientSession session(scene_lights(), kSceneGuid, session_options());
    upload(session);
    session.on_message(OpenChannelMsg{1u << 31, scene_channel_name(kSceneGuid), 100});
    ASSERT_TRUE(session.finished());
    EXPECT_EQ(session.take_result().error_kind(), ErrorKind::kFailed);

    ClientSession stray(scene_lights(), kSceneGuid, session_options());
    upload(stray);
    stray.on_message(WriteChannelMsg{3, 0, {1, 2, 3}});
    EXPECT_TRUE(stray.finished());
    EXPECT_FALSE(stray.succeeded());
}

TEST(ClientSession, BakeDoneBeforeTheChannelClosesIsRejected) {
    const std::vector<SceneLight> lights = scene_lights();
    ClientSession session(lights, kSceneGuid, session_options());
    upload(session);
    std::vector<Message> result = result_messages(lights);
    session.on_message(result[0]);
    session.on_message(result.back());  // BakeDone
    ASSERT_TRUE(session.finished());
    EXPECT_FALSE(session.succeeded());
}

TEST(ClientSession, TransportFailureEndsTheBakeOnce) {
    ClientSession session(scene_lights(), kSceneGuid, session_options());
    upload(session);
    session.fail(make_error("connection lost"));
    session.fail(make_error("a later error"));
    Result<BakeOutcome> outcome = session.take_result();
    ASSERT_FALSE(outcome);
    EXPECT_EQ(outcome.error(), "connection lost");
    EXPECT_EQ(outcome.error_kind(), ErrorKind::kFailed);
}

// The channels a session uploads, by name, with their bytes joined.
std::vector<std::pair<std::string, std::vector<uint8_t>>> uploaded_channels(const std::vector<Message>& messages) {
    std::vector<std::pair<std::string, std::vector<uint8_t>>> channels;
    std::map<uint32_t, size_t> by_id;
    for (const Message& m : messages) {
        if (auto* open = std::get_if<OpenChannelMsg>(&m)) {
            by_id[open->channel_id] = channels.size();
            channels.push_back({open->name, {}});
        } else if (auto* write = std::get_if<WriteChannelMsg>(&m)) {
            std::vector<uint8_t>& bytes = channels[by_id.at(write->channel_id)].second;
            bytes.insert(bytes.end(), write->data.begin(), write->data.end());
        }
    }
    return channels;
}

TEST(ClientSession, SendsTheGeometryChannelOnlyWhenGiven) {
    SceneGeometry geometry;
    geometry.materials.resize(1);
    geometry.materials[0].emission = {2, 2, 2};
    SurfaceTriangle t;
    t.positions[1] = {1, 0, 0};
    t.positions[2] = {0, 0, 1};
    t.normals[0] = t.normals[1] = t.normals[2] = {0, 1, 0};
    geometry.triangles = {t};
    for (bool with_geometry : {false, true}) {
        SCOPED_TRACE(with_geometry);
        ClientSessionOptions options = session_options();
        options.request.area_lights = with_geometry ? 300u : 0u;
        if (with_geometry) options.geometry = std::make_shared<const SceneGeometry>(geometry);
        ClientSession session(scene_lights(), kSceneGuid, options);
        session.start();
        drain(session);
        session.on_message(HelloAckMsg{kProtocolVersion, "server"});
        const std::vector<Message> upload = drain(session);
        const auto channels = uploaded_channels(upload);
        ASSERT_EQ(channels.size(), with_geometry ? 2u : 1u);
        EXPECT_EQ(channels[0].first, scene_channel_name(kSceneGuid));
        const BakeRequestMsg& request = std::get<BakeRequestMsg>(upload.back());
        if (!with_geometry) {
            EXPECT_TRUE(request.geometry_channel.empty());
            EXPECT_EQ(request.area_lights, 0u);
            continue;
        }
        EXPECT_EQ(channels[1].first, geometry_channel_name(kSceneGuid));
        EXPECT_EQ(channels[1].second, encode_geometry_channel(geometry));
        EXPECT_EQ(request.geometry_channel, geometry_channel_name(kSceneGuid));
        EXPECT_EQ(request.area_lights, 300u);
    }
}

// bake -o as the session asks for it: the dump is opened with the channel's
// name and size, every chunk appended as it arrives, and committed with the
// outcome; the session itself writes nothing.
TEST(ClientSession, EmitsTheResultDumpAsActionsAndCommitsItWithTheOutcome) {
    const std::vector<SceneLight> lights = scene_lights();
    const std::vector<Message> result = result_messages(lights);
    ClientSessionOptions options = session_options();
    options.write_dump = true;
    ClientSession session(lights, kSceneGuid, options);
    upload(session);
    ClientActions actions;
    for (const Message& message : result) {
        session.on_message(message);
        for (ClientAction& action : session.take_actions()) actions.push_back(std::move(action));
    }
    Result<BakeOutcome> outcome = session.take_result();
    ASSERT_TRUE(outcome) << outcome.error();
    const auto opens = actions_of<client_action::OpenDump>(actions);
    ASSERT_EQ(opens.size(), 1u);
    EXPECT_EQ(opens[0].channel_name, lightcuts_result_channel_name());
    std::vector<uint8_t> appended;
    for (const auto& append : actions_of<client_action::AppendDump>(actions))
        appended.insert(appended.end(), append.bytes.begin(), append.bytes.end());
    EXPECT_EQ(opens[0].total_bytes, appended.size());
    EXPECT_EQ(appended, encode_result_channel(outcome->tree));
    EXPECT_EQ(appended, outcome->result_channel);
    ASSERT_FALSE(actions.empty());
    EXPECT_TRUE(std::holds_alternative<client_action::OpenDump>(
        *std::find_if(actions.begin(), actions.end(), [](const ClientAction& a) {
            return !std::holds_alternative<client_action::ReportProgress>(a);
        })));
    EXPECT_TRUE(std::holds_alternative<client_action::CommitDump>(actions.back()));
    EXPECT_TRUE(actions_of<client_action::DiscardDump>(actions).empty());
    EXPECT_TRUE(actions_of<client_action::RecordChannel>(actions).empty()) << "nothing recorded unless asked";
}

// A dump that cannot be committed (or a recording that cannot be written)
// fails the bake, even after BakeDone, and the dump is discarded.
TEST(ClientSession, AnOutputThatFailsFailsTheFinishedBake) {
    const std::vector<SceneLight> lights = scene_lights();
    ClientSessionOptions options = session_options();
    options.write_dump = true;
    ClientSession session(lights, kSceneGuid, options);
    upload(session);
    for (const Message& message : result_messages(lights)) session.on_message(message);
    ASSERT_TRUE(session.succeeded());
    const ClientActions at_done = session.take_actions();
    ASSERT_FALSE(at_done.empty());
    ASSERT_TRUE(std::holds_alternative<client_action::CommitDump>(at_done.back()));

    session.fail_outputs(make_error("no space left on the device"));
    const ClientActions after = session.take_actions();
    ASSERT_EQ(after.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<client_action::DiscardDump>(after[0]));
    EXPECT_FALSE(session.succeeded());
    Result<BakeOutcome> outcome = session.take_result();
    ASSERT_FALSE(outcome);
    EXPECT_EQ(outcome.error_kind(), ErrorKind::kFailed);
}

// A transfer cut short discards the dump it had opened.
TEST(ClientSession, ABakeCutShortDiscardsItsDump) {
    const std::vector<SceneLight> lights = scene_lights();
    const std::vector<Message> result = result_messages(lights);
    ClientSessionOptions options = session_options();
    options.write_dump = true;
    ClientSession session(lights, kSceneGuid, options);
    upload(session);
    session.on_message(result[0]);  // OpenChannel
    session.on_message(result[1]);  // the first WriteChannel
    EXPECT_EQ(actions_of<client_action::OpenDump>(session.take_actions()).size(), 1u);
    session.fail(make_error("connection lost"));
    const ClientActions actions = session.take_actions();
    ASSERT_EQ(actions.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<client_action::DiscardDump>(actions[0]));
    session.fail(make_error("a second failure is ignored"));
    EXPECT_TRUE(session.take_actions().empty());
}

// --record: the channels sent are recorded when BakeRequest goes (before it
// is written, so a failed recording sends no request), the result channel at
// BakeDone; without --record nothing is.
TEST(ClientSession, RecordsEveryChannelWhenAsked) {
    const std::vector<SceneLight> lights = scene_lights();
    ClientSessionOptions options = session_options();
    options.record_channels = true;
    ClientSession session(lights, kSceneGuid, options);
    session.start();
    drain(session);
    session.on_message(HelloAckMsg{kProtocolVersion, "server"});
    EXPECT_TRUE(session.take_actions().empty());
    std::optional<Message> message;
    while ((message = session.next_message()) && !std::holds_alternative<BakeRequestMsg>(*message))
        EXPECT_TRUE(session.take_actions().empty()) << "recorded only with the request";
    ASSERT_TRUE(message);
    const auto sent = actions_of<client_action::RecordChannel>(session.take_actions());
    ASSERT_EQ(sent.size(), 1u);
    EXPECT_EQ(sent[0].name, scene_channel_name(kSceneGuid));
    EXPECT_EQ(sent[0].bytes, encode_scene_channel(lights));

    for (const Message& m : result_messages(lights)) session.on_message(m);
    const auto received = actions_of<client_action::RecordChannel>(session.take_actions());
    Result<BakeOutcome> outcome = session.take_result();
    ASSERT_TRUE(outcome) << outcome.error();
    ASSERT_EQ(received.size(), 1u);
    EXPECT_EQ(received[0].name, lightcuts_result_channel_name());
    EXPECT_EQ(received[0].bytes, outcome->result_channel);
}

}  // namespace
}  // namespace lc::client
