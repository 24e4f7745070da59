// End to end over loopback: a separately started lightmass_server process and
// the client library, plus raw peers that misbehave on purpose.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <random>
#include <thread>

#include <stdlib.h>

#include "editor_client/bake/bake_client.h"
#include "editor_client/bake/server_process.h"
#include "editor_client/bake/tree_store.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/codec.h"
#include "protocol/dump.h"
#include "raw_client.h"
#include "test_paths.h"

namespace lc {
namespace {

using client::BakeClientOptions;
using client::ServerProcess;

std::string server_binary() { return (test::bin_dir() / "lightmass_server").string(); }

std::unique_ptr<ServerProcess> start_server(std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"--quiet"};
    if (std::find(extra.begin(), extra.end(), "--listen") == extra.end()) {
        args.push_back("--listen");
        args.push_back("127.0.0.1:0");
    }
    args.insert(args.end(), extra.begin(), extra.end());
    auto server = ServerProcess::spawn_with(server_binary(), args);
    EXPECT_TRUE(server.ok()) << (server.ok() ? "" : server.error());
    return server.ok() ? std::move(server.value()) : nullptr;
}

SceneLight point_light(float x, float y, float z, float intensity, float range, uint32_t id) {
    SceneLight light;
    light.guid = Guid{0x1000u + id, 0, 0, id};
    light.type = LightType::kPoint;
    light.position = {x, y, z};
    light.intensity = intensity;
    light.range = range;
    return light;
}

// The thesis's Figure 9.1: five point lights, radius 250, z = 150.
std::vector<SceneLight> figure_9_1_lights() {
    return {point_light(-300, 0, 150, 5000, 250, 0), point_light(-225, -45, 150, 7500, 250, 1),
            point_light(-300, 150, 150, 5000, 250, 2), point_light(0, 0, 150, 5000, 250, 3),
            point_light(150, 0, 150, 5000, 250, 4)};
}

std::vector<SceneLight> random_lights(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-50.0f, 50.0f), power(1.0f, 100.0f);
    std::vector<SceneLight> lights;
    for (size_t i = 0; i < n; ++i)
        lights.push_back(point_light(pos(rng), pos(rng), pos(rng), power(rng), 0.0f, static_cast<uint32_t>(i)));
    return lights;
}

BakeClientOptions options_for(const ServerProcess& server) {
    BakeClientOptions options;
    options.server = server.address();
    options.timeout_seconds = 120.0;
    return options;
}

const Guid kSceneGuid{1, 2, 3, 4};

const LightTreeNode& child(const LightTree& tree, const LightTreeNode& node, bool left) {
    return tree.nodes.at(static_cast<size_t>(left ? node.left : node.right));
}

TEST(BakeRoundTrip, Figure91TreeFromSeparateServer) {
    auto server = start_server();
    ASSERT_TRUE(server);
    BakeClientOptions options = options_for(*server);
    options.representative_rule = RepresentativeRule::kThesisFirst;
    auto outcome = client::bake_lights(figure_9_1_lights(), kSceneGuid, options);
    ASSERT_TRUE(outcome.ok()) << outcome.error();
    const LightTree& tree = outcome->tree;
    ASSERT_EQ(tree.nodes.size(), 9u);
    EXPECT_EQ(tree.leaf_count, 5u);
    EXPECT_TRUE(outcome->done.exact);
    EXPECT_EQ(outcome->result_channel_name, lightcuts_result_channel_name());

    // Root: 27500, radius 700, at (-300, 0).
    const LightTreeNode& root = tree.nodes[0];
    EXPECT_FLOAT_EQ(root.brightness, 27500.0f);
    EXPECT_NEAR(root.radius, 700.0f, 1e-3);
    EXPECT_FLOAT_EQ(root.position.x, -300.0f);
    EXPECT_FLOAT_EQ(root.position.y, 0.0f);
    // Children: {(-300,0),(-225,-45),(-300,150)} -> 17500 / 400, and {(0,0),(150,0)} -> 10000 / 400.
    const LightTreeNode& a = child(tree, root, true);
    const LightTreeNode& b = child(tree, root, false);
    EXPECT_FLOAT_EQ(a.brightness, 17500.0f);
    EXPECT_NEAR(a.radius, 400.0f, 1e-3);
    EXPECT_FLOAT_EQ(b.brightness, 10000.0f);
    EXPECT_NEAR(b.radius, 400.0f, 1e-3);
    EXPECT_FLOAT_EQ(b.position.x, 0.0f);
    // Inside a: the pair {(-300,0),(-225,-45)} -> 12500, radius 337.464, and (-300,150) carried up.
    const LightTreeNode& pair = child(tree, a, true);
    const LightTreeNode& carried = child(tree, a, false);
    EXPECT_FLOAT_EQ(pair.brightness, 12500.0f);
    EXPECT_NEAR(pair.radius, 337.464f, 1e-3);
    EXPECT_TRUE(carried.is_leaf());
    EXPECT_FLOAT_EQ(carried.position.y, 150.0f);
    EXPECT_TRUE(child(tree, b, true).is_leaf());
    EXPECT_TRUE(child(tree, b, false).is_leaf());
}

TEST(BakeRoundTrip, SameInputAndSeedGiveIdenticalChannelBytes) {
    auto server = start_server();
    ASSERT_TRUE(server);
    auto lights = random_lights(300, 11);
    BakeClientOptions options = options_for(*server);
    options.seed = 42;
    auto first = client::bake_lights(lights, kSceneGuid, options);
    auto second = client::bake_lights(lights, kSceneGuid, options);
    ASSERT_TRUE(first.ok()) << first.error();
    ASSERT_TRUE(second.ok()) << second.error();
    EXPECT_EQ(first->result_channel, second->result_channel);
    EXPECT_EQ(first->tree.nodes.size(), 599u);
}

TEST(BakeRoundTrip, SpawnedServerBakesAndRecordsDumps) {
    auto dir = test::make_temp_dir("record");
    BakeClientOptions options;
    options.spawn_server = true;
    options.record_dir = dir;
    ::setenv("LC_SERVER_BIN", server_binary().c_str(), 1);
    auto outcome = client::bake_lights(random_lights(40, 5), kSceneGuid, options);
    ASSERT_TRUE(outcome.ok()) << outcome.error();
    auto result_dump = read_dump(dump_path_for(dir, lightcuts_result_channel_name()));
    ASSERT_TRUE(result_dump.ok()) << result_dump.error();
    EXPECT_EQ(result_dump->payload, outcome->result_channel);
    auto scene_dump = read_dump(dump_path_for(dir, scene_channel_name(kSceneGuid)));
    ASSERT_TRUE(scene_dump.ok()) << scene_dump.error();
    auto lights = decode_scene_channel(scene_dump->payload);
    ASSERT_TRUE(lights.ok()) << lights.error();
    EXPECT_EQ(lights->size(), 40u);
}

TEST(BakeRoundTrip, VersionMismatchIsRefusedNamingBothVersions) {
    auto server = start_server();
    ASSERT_TRUE(server);
    test::RawClient peer(test::port_of(server->address()));
    Guid other{0xDEADBEEFu, 1, 2, 3};
    ASSERT_TRUE(peer.send(HelloMsg{other, "old client", ""}));
    auto reply = peer.receive();
    ASSERT_TRUE(reply.has_value());
    auto* error = std::get_if<ErrorMsg>(&*reply);
    ASSERT_NE(error, nullptr);
    EXPECT_EQ(error->code, ErrorCode::kVersionMismatch);
    EXPECT_NE(error->text.find(other.to_hex()), std::string::npos) << error->text;
    EXPECT_NE(error->text.find(kProtocolVersion.to_hex()), std::string::npos) << error->text;
    EXPECT_TRUE(peer.wait_closed());
}

TEST(BakeRoundTrip, SceneChannelOfAnotherVersionIsRefused) {
    auto server = start_server();
    ASSERT_TRUE(server);
    test::RawClient peer(test::port_of(server->address()));
    ASSERT_TRUE(peer.send(HelloMsg{kProtocolVersion, "test", ""}));
    ASSERT_TRUE(peer.receive().has_value());
    Guid old_format{7, 7, 7, 7};
    ASSERT_TRUE(peer.send(OpenChannelMsg{1, create_channel_name(kSceneGuid, old_format, "scene"), 4}));
    auto reply = peer.receive();
    ASSERT_TRUE(reply.has_value());
    auto* error = std::get_if<ErrorMsg>(&*reply);
    ASSERT_NE(error, nullptr);
    EXPECT_EQ(error->code, ErrorCode::kVersionMismatch);
    EXPECT_NE(error->text.find(old_format.to_hex()), std::string::npos) << error->text;
    EXPECT_NE(error->text.find(kSceneFormatVersionGuid.to_hex()), std::string::npos) << error->text;
}

TEST(BakeRoundTrip, MalformedClientDoesNotDisturbAnotherClientsBake) {
    auto server = start_server({"--threads", "2"});
    ASSERT_TRUE(server);
    auto lights = random_lights(1500, 3);
    Result<client::BakeOutcome> outcome;
    std::thread good([&] { outcome = client::bake_lights(lights, kSceneGuid, options_for(*server)); });

    // An over-cap size header: refused before any allocation, connection closed.
    {
        test::RawClient bad(test::port_of(server->address()));
        std::vector<uint8_t> huge_header = {0xFF, 0xFF, 0xFF, 0x7F};
        bad.send_bytes(huge_header);
        EXPECT_TRUE(bad.wait_closed());
    }
    // A frame of garbage after a valid Hello.
    {
        test::RawClient bad(test::port_of(server->address()));
        ASSERT_TRUE(bad.send(HelloMsg{kProtocolVersion, "bad", ""}));
        ASSERT_TRUE(bad.receive().has_value());
        std::vector<uint8_t> garbage(64, 0xAB);
        bad.send_bytes(frame_bytes(garbage));
        auto reply = bad.receive();
        ASSERT_TRUE(reply.has_value());
        auto* error = std::get_if<ErrorMsg>(&*reply);
        ASSERT_NE(error, nullptr);
        EXPECT_EQ(error->code, ErrorCode::kMalformedFrame);
        EXPECT_TRUE(bad.wait_closed());
    }
    // A message before Hello.
    {
        test::RawClient bad(test::port_of(server->address()));
        ASSERT_TRUE(bad.send(CancelMsg{1}));
        auto reply = bad.receive();
        ASSERT_TRUE(reply.has_value());
        EXPECT_TRUE(std::holds_alternative<ErrorMsg>(*reply));
        EXPECT_TRUE(bad.wait_closed());
    }
    good.join();
    ASSERT_TRUE(outcome.ok()) << outcome.error();
    EXPECT_EQ(outcome->tree.leaf_count, 1500u);
}

TEST(BakeRoundTrip, StalledPeerIsDropped) {
    auto server = start_server({"--read-timeout-ms", "300"});
    ASSERT_TRUE(server);
    test::RawClient peer(test::port_of(server->address()), std::chrono::seconds(5));
    std::vector<uint8_t> half_header = {0x10, 0x00};
    ASSERT_TRUE(peer.send_bytes(half_header));
    auto start = std::chrono::steady_clock::now();
    EXPECT_TRUE(peer.wait_closed());
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(4));
}

TEST(BakeRoundTrip, InvalidSceneIsRefusedAndPreviousTreeKept) {
    auto server = start_server();
    ASSERT_TRUE(server);
    client::TreeStore store;
    ASSERT_TRUE(store.import(client::bake_lights(random_lights(20, 1), kSceneGuid, options_for(*server))).ok());
    auto before = store.current();
    ASSERT_EQ(before->leaf_count, 20u);

    // Bypass client-side validation with a raw peer: the server must refuse NaN.
    auto lights = random_lights(5, 2);
    lights[3].intensity = std::nanf("");
    test::RawClient peer(test::port_of(server->address()));
    ASSERT_TRUE(peer.send(HelloMsg{kProtocolVersion, "test", ""}));
    ASSERT_TRUE(peer.receive().has_value());
    auto bytes = encode_scene_channel(lights);
    ASSERT_TRUE(peer.send(OpenChannelMsg{1, scene_channel_name(kSceneGuid), bytes.size()}));
    ASSERT_TRUE(peer.send(WriteChannelMsg{1, 0, bytes}));
    ASSERT_TRUE(peer.send(CloseChannelMsg{1}));
    auto reply = peer.receive();
    ASSERT_TRUE(reply.has_value());
    auto* error = std::get_if<ErrorMsg>(&*reply);
    ASSERT_NE(error, nullptr);
    EXPECT_EQ(error->code, ErrorCode::kInvalidScene);
    EXPECT_NE(error->text.find("3"), std::string::npos) << "error should name the light: " << error->text;

    // The client refuses the same scene itself, and the store keeps its tree.
    Status failed = store.import(client::bake_lights(lights, kSceneGuid, options_for(*server)));
    EXPECT_FALSE(failed.ok());
    EXPECT_EQ(store.current(), before);
    EXPECT_EQ(store.generation(), 1u);

    // The same connection still serves a valid bake request afterwards.
    auto good = encode_scene_channel(random_lights(4, 9));
    ASSERT_TRUE(peer.send(OpenChannelMsg{2, scene_channel_name(Guid{9, 9, 9, 9}), good.size()}));
    ASSERT_TRUE(peer.send(WriteChannelMsg{2, 0, good}));
    ASSERT_TRUE(peer.send(CloseChannelMsg{2}));
    BakeRequestMsg request;
    request.bake_id = 5;
    request.scene_channel = scene_channel_name(Guid{9, 9, 9, 9});
    ASSERT_TRUE(peer.send(request));
    bool done = false;
    while (auto m = peer.receive()) {
        if (auto* d = std::get_if<BakeDoneMsg>(&*m)) {
            EXPECT_EQ(d->node_count, 7u);
            done = true;
            break;
        }
        ASSERT_FALSE(std::holds_alternative<ErrorMsg>(*m)) << std::get<ErrorMsg>(*m).text;
    }
    EXPECT_TRUE(done);
}

TEST(BakeRoundTrip, CancelStopsTheBakeAndServerKeepsServing) {
    auto server = start_server();
    ASSERT_TRUE(server);
    std::atomic<bool> cancel{false};
    BakeClientOptions options = options_for(*server);
    options.builder = BuilderKind::kOptimalPair;
    options.pairing = PairingMode::kExact;
    options.cancel = &cancel;
    options.on_progress = [&](const ProgressMsg&) { cancel.store(true); };
    auto outcome = client::bake_lights(random_lights(6000, 4), kSceneGuid, options);
    ASSERT_FALSE(outcome.ok());
    EXPECT_EQ(outcome.error_kind(), ErrorKind::kCancelled) << outcome.error();

    auto after = client::bake_lights(random_lights(10, 4), kSceneGuid, options_for(*server));
    ASSERT_TRUE(after.ok()) << after.error();
}

TEST(BakeRoundTrip, TokenRequiredOffLoopback) {
    // Listening on all interfaces without a token is refused at start, and so
    // is a token without TLS (TlsChannel.OffLoopbackNeedsTokenAndTls serves
    // off loopback with both); the token itself is checked here on loopback.
    auto refused = ServerProcess::spawn_with(server_binary(), {"--listen", "0.0.0.0:0"});
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().find("did not report"), std::string::npos) << refused.error();

    auto dir = test::make_temp_dir("token");
    auto token_path = dir / "token";
    std::ofstream(token_path) << "correct-horse-battery-staple\n";
    auto no_tls = ServerProcess::spawn_with(server_binary(),
                                            {"--listen", "0.0.0.0:0", "--token-file", token_path.string()});
    ASSERT_FALSE(no_tls.ok());
    auto server = start_server({"--token-file", token_path.string()});
    ASSERT_TRUE(server);
    BakeClientOptions options;
    options.server = "127.0.0.1:" + std::to_string(test::port_of(server->address()));

    auto no_token = client::bake_lights(random_lights(3, 1), kSceneGuid, options);
    ASSERT_FALSE(no_token.ok());
    EXPECT_NE(no_token.error().find("token"), std::string::npos) << no_token.error();

    auto wrong_path = dir / "wrong";
    std::ofstream(wrong_path) << "incorrect-horse-battery\n";
    options.token_file = wrong_path;
    auto wrong = client::bake_lights(random_lights(3, 1), kSceneGuid, options);
    ASSERT_FALSE(wrong.ok());
    EXPECT_NE(wrong.error().find("authentication"), std::string::npos) << wrong.error();

    options.token_file = token_path;
    auto right = client::bake_lights(random_lights(3, 1), kSceneGuid, options);
    ASSERT_TRUE(right.ok()) << right.error();
}

TEST(BakeRoundTrip, OneTokenFileAuthenticatesOnBothSides) {
    // White space around the token is dropped by both programs (one reader,
    // protocol/token_file.h): the server's file and the client's file differ
    // only in it, and the bake authenticates.
    auto dir = test::make_temp_dir("token_space");
    auto server_token = dir / "server_token";
    auto client_token = dir / "client_token";
    std::ofstream(server_token) << "correct-horse-battery-staple\n";
    std::ofstream(client_token) << "  correct-horse-battery-staple \r\n";
    auto server = start_server({"--token-file", server_token.string()});
    ASSERT_TRUE(server);
    BakeClientOptions options;
    options.server = "127.0.0.1:" + std::to_string(test::port_of(server->address()));
    options.token_file = client_token;
    auto baked = client::bake_lights(random_lights(3, 1), kSceneGuid, options);
    EXPECT_TRUE(baked.ok()) << baked.error();

    // A short token is refused by the client before it connects, as the server refuses it at start.
    auto short_token = dir / "short_token";
    std::ofstream(short_token) << "  short\n";
    options.token_file = short_token;
    auto refused = client::bake_lights(random_lights(3, 1), kSceneGuid, options);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().find("too short"), std::string::npos) << refused.error();
    EXPECT_FALSE(ServerProcess::spawn_with(server_binary(), {"--token-file", short_token.string()}).ok());
}

TEST(BakeRoundTrip, ServerStopsCleanlyOnSigterm) {
    auto server = start_server();
    ASSERT_TRUE(server);
    EXPECT_EQ(server->terminate(), 0);
}

}  // namespace
}  // namespace lc
