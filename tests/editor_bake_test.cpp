// The editor's background bakes against a real lightmass_server: progress,
// atomic import, failure keeping the previous tree, cancel, edits during a
// bake, and a scripted bake.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <set>
#include <thread>

#include "editor_client/bake/server_process.h"
#include "editor_client/editor/editor_session.h"
#include "editor_client/editor/overlay_text.h"
#include "editor_client/editor/script_runner.h"
#include "editor_client/scene/scene_generator.h"
#include "test_paths.h"

namespace lc::client {
namespace {

std::string server_binary() { return (test::bin_dir() / "lightmass_server").string(); }

std::unique_ptr<ServerProcess> start_server() {
    auto server = ServerProcess::spawn_with(
        server_binary(), {"--quiet", "--listen", "127.0.0.1:0", "--threads", "2"});
    EXPECT_TRUE(server.ok()) << (server.ok() ? "" : server.error());
    return server.ok() ? std::move(server.value()) : nullptr;
}

EditorSessionOptions options_for(const ServerProcess& server) {
    EditorSessionOptions options;
    options.bake.server = server.address();
    options.bake.timeout_seconds = 120.0;
    return options;
}

LightLayoutOptions room_layout(uint32_t count, uint64_t seed) {
    LightLayoutOptions layout;
    layout.count = count;
    layout.seed = seed;
    layout.box_min = kRoomLightBoxMin;
    layout.box_max = kRoomLightBoxMax;
    return layout;
}

// Polls like the window does, once per "frame", recording what it saw.
BakeReport poll_until_done(EditorSession& session, std::set<std::string>* stages = nullptr) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (std::chrono::steady_clock::now() < deadline) {
        if (auto progress = session.baking().bake_progress(); progress && stages) {
            EXPECT_GE(progress->percent, 0.0f);
            EXPECT_LE(progress->percent, 100.0f);
            if (!progress->stage.empty()) stages->insert(progress->stage);
        }
        if (std::optional<BakeReport> report = session.baking().poll_bake()) return *report;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ADD_FAILURE() << "bake did not finish in 120 s";
    return {};
}

class RecordingHost final : public EditorHost {
public:
    Status screenshot(const std::filesystem::path&) override { return Ok{}; }
    void request_quit() override {}
};

TEST(EditorBake, BakeImportsTheTreeOfTheCurrentLights) {
    auto server = start_server();
    ASSERT_TRUE(server);
    EditorSession session(make_room_scene(), options_for(*server));
    ASSERT_EQ(session.edits().add_procedural_lights(room_layout(200, 1)).value(), 200u);
    ASSERT_TRUE(
        session.edits().add_light(SceneLight{.position = {0, 2, 0}, .intensity = 3.0f, .classic = true}));
    EXPECT_FALSE(session.tree_matches_scene());
    EXPECT_EQ(session.baking().tree_generation(), 0u);

    ASSERT_TRUE(session.start_bake());
    EXPECT_TRUE(session.baking().bake_running());
    EXPECT_FALSE(session.start_bake().ok());  // one bake at a time
    std::set<std::string> stages;
    BakeReport report = poll_until_done(session, &stages);
    ASSERT_TRUE(report.succeeded) << report.error;
    EXPECT_FALSE(session.baking().bake_running());
    EXPECT_FALSE(stages.empty());  // progress messages reached the UI side
    EXPECT_EQ(report.light_count, 201u);
    EXPECT_EQ(report.node_count, 2u * 200u - 1u);  // the classic light stays out
    EXPECT_GT(report.total_ms, 0.0);
    EXPECT_EQ(session.baking().tree_generation(), 1u);
    ASSERT_TRUE(session.baking().tree());
    EXPECT_EQ(session.baking().tree()->leaf_count, 200u);
    EXPECT_TRUE(session.tree_matches_scene());
    ASSERT_TRUE(session.baking().last_bake());
    EXPECT_TRUE(session.baking().last_bake()->succeeded);

    // The tree's leaves are the scene's non-classic lights, by GUID.
    std::set<Guid> scene_guids, leaf_guids;
    for (const SceneLight& light : session.scene().lights)
        if (!light.classic) scene_guids.insert(light.guid);
    for (const LightTreeNode& node : session.baking().tree()->nodes)
        if (node.is_leaf()) leaf_guids.insert(node.guid);
    EXPECT_EQ(scene_guids, leaf_guids);

    const std::vector<std::string> overlay = overlay_lines(session, FrameInfo{});
    auto shows = [&](const std::string& text) {
        for (const std::string& line : overlay)
            if (line.find(text) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(shows("tree: 399 nodes, 200 leaves")) << overlay[4];
    EXPECT_FALSE(shows("stale"));
    EXPECT_TRUE(shows("last bake: ")) << overlay.back();

    // An edit makes the tree stale until the next bake.
    ASSERT_TRUE(session.edits().remove_light(0));
    EXPECT_FALSE(session.tree_matches_scene());
    ASSERT_TRUE(session.start_bake());
    report = poll_until_done(session);
    ASSERT_TRUE(report.succeeded) << report.error;
    EXPECT_EQ(session.baking().tree()->leaf_count, 199u);
    EXPECT_EQ(session.baking().tree_generation(), 2u);
    EXPECT_TRUE(session.tree_matches_scene());
}

// Build Lighting with indirect light chosen in the panel (issue 16): the
// solver's stage reaches the progress bar (the panel draws bake_progress(),
// the last message, so a stage shorter than a frame may pass unseen), and the
// tree holds the bounced light, patches or VPLs.
TEST(EditorBake, BuildLightingBakesIndirectLightWithItsStageInTheProgress) {
    auto server = start_server();
    ASSERT_TRUE(server);
    EditorSessionOptions options = options_for(*server);
    options.bake.area_lights = 256;
    options.bake.indirect.patch_size = 0.5f;
    options.bake.indirect.vpl_count = 200000;  // long enough for the 5 ms polls to see the stage
    options.bake.indirect.bounces = 2;
    EditorSession session(make_cornell_emissive_scene(), options);
    for (IndirectMethod method : {IndirectMethod::kRadiosity, IndirectMethod::kVpl}) {
        session.baking().set_indirect(method);
        ASSERT_TRUE(session.start_bake());
        std::set<std::string> stages;
        BakeReport report = poll_until_done(session, &stages);
        ASSERT_TRUE(report.succeeded) << report.error;
        const std::string solver = method == IndirectMethod::kRadiosity ? "radiosity" : "indirect";
        EXPECT_TRUE(stages.count(solver)) << solver;
        size_t patches = 0, vpls = 0;
        for (const LightTreeNode& node : session.baking().tree()->nodes) {
            if (!node.is_leaf() || !node.flags.indirect()) continue;
            patches += node.flags.patch();
            vpls += !node.flags.patch();
        }
        if (method == IndirectMethod::kRadiosity) {
            EXPECT_GT(patches, 10u);
            EXPECT_EQ(vpls, 0u);
        } else {
            EXPECT_GT(vpls, 100u);
            EXPECT_EQ(patches, 0u);
        }
    }
}

TEST(EditorBake, FailedBakeKeepsThePreviousTreeAndTheError) {
    auto server = start_server();
    ASSERT_TRUE(server);
    EditorSession session(make_room_scene(), options_for(*server));
    ASSERT_TRUE(session.edits().add_procedural_lights(room_layout(50, 2)));
    ASSERT_TRUE(session.start_bake());
    BakeReport first = poll_until_done(session);
    ASSERT_TRUE(first.succeeded) << first.error;
    const std::shared_ptr<const LightTree> before = session.baking().tree();

    // The server goes away: the next bake fails, and nothing is lost.
    server->terminate();
    ASSERT_TRUE(session.edits().add_procedural_lights(room_layout(10, 3)));
    ASSERT_TRUE(session.start_bake());
    BakeReport failed = poll_until_done(session);
    EXPECT_FALSE(failed.succeeded);
    EXPECT_FALSE(failed.cancelled);
    EXPECT_FALSE(failed.error.empty());
    EXPECT_EQ(session.baking().tree(), before);
    EXPECT_EQ(session.baking().tree()->leaf_count, 50u);
    EXPECT_EQ(session.baking().tree_generation(), 1u);
    ASSERT_TRUE(session.baking().last_bake());
    EXPECT_EQ(session.baking().last_bake()->error, failed.error);
    EXPECT_FALSE(session.tree_matches_scene());
}

TEST(EditorBake, CancelStopsTheBakeAndKeepsTheOldTree) {
    auto server = start_server();
    ASSERT_TRUE(server);
    EditorSessionOptions options = options_for(*server);
    options.bake.pairing = PairingMode::kExact;  // slow enough to cancel in flight
    EditorSession session(make_room_scene(), options);
    ASSERT_TRUE(session.edits().add_procedural_lights(room_layout(16, 4)));
    ASSERT_TRUE(session.start_bake());
    ASSERT_TRUE(poll_until_done(session).succeeded);
    const std::shared_ptr<const LightTree> before = session.baking().tree();

    ASSERT_TRUE(session.edits().add_procedural_lights(room_layout(6000, 5)));
    ASSERT_TRUE(session.start_bake());
    // Cancel once the server reports progress (the bake is really running).
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
        auto progress = session.baking().bake_progress();
        if (!progress || !progress->stage.empty()) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    session.baking().cancel_bake();
    BakeReport report = poll_until_done(session);
    EXPECT_FALSE(report.succeeded);
    EXPECT_TRUE(report.cancelled) << report.error;  // the outcome's code, not its text
    EXPECT_EQ(session.baking().tree(), before);

    // The server still serves: a new bake after the cancel succeeds.
    ASSERT_TRUE(session.edits().undo());
    ASSERT_TRUE(session.start_bake());
    EXPECT_TRUE(poll_until_done(session).succeeded);
}

TEST(EditorBake, EditsDuringABakeLeaveTheNewTreeMarkedStale) {
    auto server = start_server();
    ASSERT_TRUE(server);
    EditorSession session(make_room_scene(), options_for(*server));
    ASSERT_TRUE(session.edits().add_procedural_lights(room_layout(300, 6)));
    ASSERT_TRUE(session.start_bake());
    ASSERT_TRUE(session.edits().add_light(SceneLight{.position = {1, 1, 1}, .intensity = 2.0f}));
    BakeReport report = poll_until_done(session);
    ASSERT_TRUE(report.succeeded) << report.error;
    EXPECT_EQ(session.baking().tree()->leaf_count, 300u);  // what was sent
    EXPECT_FALSE(session.tree_matches_scene());
}

TEST(EditorBake, SpawnedServerLivesForTheSession) {
    ::setenv("LC_SERVER_BIN", server_binary().c_str(), 1);
    EditorSessionOptions options;
    options.bake.spawn_server = true;
    EditorSession session(make_room_scene(), options);
    EXPECT_TRUE(session.baking().has_server());
    ASSERT_TRUE(session.edits().add_procedural_lights(room_layout(30, 7)));
    EXPECT_EQ(session.baking().server_description(), "local (started at the first bake)");
    std::string first_server;
    for (int i = 0; i < 2; ++i) {
        ASSERT_TRUE(session.start_bake());
        BakeReport report = session.baking().wait_for_bake().value();
        ASSERT_TRUE(report.succeeded) << report.error;
        if (i == 0) first_server = session.baking().server_description();
    }
    EXPECT_EQ(first_server.rfind("local 127.0.0.1:", 0), 0u) << first_server;
    EXPECT_EQ(session.baking().server_description(), first_server);  // the same process both times
    EXPECT_EQ(session.baking().tree_generation(), 2u);
}

TEST(EditorBake, ScriptedBakeWaitsThenContinues) {
    auto server = start_server();
    ASSERT_TRUE(server);
    auto script = parse_editor_script(
        "add-lights 64 grid 1\n"
        "bake\n"
        "mode lightcuts\n"
        "remove-light 0\n"
        "bake\n");
    ASSERT_TRUE(script.ok()) << script.error();
    EditorSession session(make_room_scene(), options_for(*server));
    RecordingHost host;
    ScriptRunner runner(std::move(script.value()), "bake.txt");
    // Step like a frame loop: the runner waits while the bake is in flight.
    int waiting_frames = 0;
    ScriptState state = ScriptState::kRunning;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (std::chrono::steady_clock::now() < deadline) {
        session.baking().poll_bake();
        state = runner.step(session, host);
        if (state != ScriptState::kWaiting) break;
        ++waiting_frames;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    EXPECT_EQ(state, ScriptState::kFinished) << runner.error();
    EXPECT_GE(waiting_frames, 2);
    EXPECT_EQ(session.view().mode, RenderMode::kLightcuts);
    EXPECT_EQ(session.baking().tree_generation(), 2u);
    EXPECT_EQ(session.baking().tree()->leaf_count, 63u);
    EXPECT_TRUE(session.tree_matches_scene());

    // A failing scripted bake stops the script at its line.
    server->terminate();
    auto again = parse_editor_script("add-light point 0 1 0 1 1 1 5\nbake\nquit\n");
    ASSERT_TRUE(again.ok());
    ScriptRunner failing(std::move(again.value()), "again.txt");
    EXPECT_EQ(run_script_to_end(failing, session, host), ScriptState::kFailed);
    EXPECT_EQ(failing.error().rfind("again.txt:2: bake failed", 0), 0u) << failing.error();
    EXPECT_EQ(session.baking().tree()->leaf_count, 63u);
}

}  // namespace
}  // namespace lc::client
