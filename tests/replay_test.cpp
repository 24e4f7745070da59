// Replays channel dumps recorded by the real programs (scripts/tools/record_replay_data.sh):
// the recorded scene channel, baked again, must give the recorded result channel
// byte for byte; the client's and the server's recordings must agree; the
// client must import the recorded result.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "editor_client/bake/tree_store.h"
#include "lightmass_server/mpi/bake_dispatch.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/dump.h"
#include "test_paths.h"

namespace lc {
namespace {

namespace fs = std::filesystem;

struct ReplayCase {
    fs::path dir;
    bake::BuildOptions options;
};

std::vector<ReplayCase> replay_cases() {
    std::vector<ReplayCase> cases;
    fs::path root = test::data_dir() / "replay";
    if (!fs::is_directory(root)) return cases;
    for (const auto& entry : fs::directory_iterator(root)) {
        if (!entry.is_directory()) continue;
        std::ifstream in(entry.path() / "case.json");
        nlohmann::json j = nlohmann::json::parse(in);
        ReplayCase c;
        c.dir = entry.path();
        std::string builder = j.at("builder");
        c.options.builder = builder == "agglomerative" ? BuilderKind::kAgglomerative
                            : builder == "lbvh"        ? BuilderKind::kLbvh
                                                       : BuilderKind::kOptimalPair;
        c.options.representative_rule = j.at("representative") == "thesis-first" ? RepresentativeRule::kThesisFirst
                                                                                 : RepresentativeRule::kIntensity;
        c.options.seed = j.at("seed");
        cases.push_back(c);
    }
    std::sort(cases.begin(), cases.end(), [](const ReplayCase& a, const ReplayCase& b) { return a.dir < b.dir; });
    return cases;
}

// The one dump in `dir` whose channel has the given extension.
fs::path find_dump(const fs::path& dir, const std::string& extension) {
    for (const auto& entry : fs::directory_iterator(dir)) {
        auto dump = read_dump(entry.path());
        if (!dump) continue;
        auto name = ChannelName::parse(dump->channel_name);
        if (name && name->extension == extension) return entry.path();
    }
    return {};
}

TEST(Replay, RecordedCasesArePresent) {
    // The suite must not pass vacuously: the recorded cases ship with the repository.
    EXPECT_GE(replay_cases().size(), 3u);
}

TEST(Replay, SceneChannelBakesToTheRecordedResultByteForByte) {
    for (const ReplayCase& c : replay_cases()) {
        SCOPED_TRACE(c.dir.string());
        auto scene_dump = read_dump(find_dump(c.dir / "server", kSceneExtension));
        ASSERT_TRUE(scene_dump.ok()) << scene_dump.error();
        auto result_dump = read_dump(find_dump(c.dir / "server", kLightcutsExtension));
        ASSERT_TRUE(result_dump.ok()) << result_dump.error();
        EXPECT_EQ(result_dump->channel_name, lightcuts_result_channel_name());

        auto lights = decode_scene_channel(scene_dump->payload);
        ASSERT_TRUE(lights.ok()) << lights.error();
        auto built = bake::build_light_tree(*lights, c.options, [](std::string_view, double) { return true; });
        ASSERT_TRUE(built.ok()) << built.error();
        std::vector<uint8_t> replayed = encode_result_channel(built->tree);
        EXPECT_EQ(replayed.size(), result_dump->payload.size());
        EXPECT_TRUE(replayed == result_dump->payload) << "the builder no longer reproduces the recorded tree; "
                                                         "if the change is deliberate, run scripts/tools/record_replay_data.sh";
    }
}

// A bake with no geometry channel (a scene with no emissive surface) goes
// through the bake pipeline, area-light stage included, to today's tree.
TEST(Replay, BakeWithoutGeometryGivesTheRecordedResultByteForByte) {
    for (const ReplayCase& c : replay_cases()) {
        SCOPED_TRACE(c.dir.string());
        auto scene_dump = read_dump(find_dump(c.dir / "server", kSceneExtension));
        auto result_dump = read_dump(find_dump(c.dir / "server", kLightcutsExtension));
        ASSERT_TRUE(scene_dump.ok() && result_dump.ok());
        auto lights = decode_scene_channel(scene_dump->payload);
        ASSERT_TRUE(lights.ok()) << lights.error();
        bake::BakeInputs inputs;
        inputs.lights = std::make_shared<const std::vector<SceneLight>>(std::move(*lights));
        inputs.build = c.options;
        auto built = bake::run_bake(inputs, [](std::string_view, double) { return true; });
        ASSERT_TRUE(built.ok()) << built.error();
        EXPECT_TRUE(encode_result_channel(built->tree) == result_dump->payload);
        EXPECT_EQ(built->report.effects,
                  (std::vector<std::string>{"area lights: skipped: no drawn triangle emits power",
                                            "indirect: skipped: no bounce requested"}));
    }
}

TEST(Replay, ClientAndServerRecordedTheSameBytes) {
    for (const ReplayCase& c : replay_cases()) {
        SCOPED_TRACE(c.dir.string());
        for (const char* extension : {kSceneExtension, kLightcutsExtension}) {
            auto server = read_dump(find_dump(c.dir / "server", extension));
            auto client = read_dump(find_dump(c.dir / "client", extension));
            ASSERT_TRUE(server.ok() && client.ok());
            EXPECT_EQ(server->channel_name, client->channel_name);
            EXPECT_TRUE(server->payload == client->payload) << extension;
        }
    }
}

TEST(Replay, ClientImportsTheRecordedResult) {
    for (const ReplayCase& c : replay_cases()) {
        SCOPED_TRACE(c.dir.string());
        client::TreeStore store;
        Status imported = store.import_dump(find_dump(c.dir / "client", kLightcutsExtension));
        ASSERT_TRUE(imported.ok()) << imported.error();
        EXPECT_GT(store.current()->nodes.size(), 0u);
        EXPECT_EQ(store.generation(), 1u);
    }
}

TEST(Replay, CorruptedDumpIsRefusedAndTheTreeKept) {
    auto cases = replay_cases();
    ASSERT_FALSE(cases.empty());
    auto source = find_dump(cases[0].dir / "client", kLightcutsExtension);
    auto dir = test::make_temp_dir("replay");
    client::TreeStore store;
    ASSERT_TRUE(store.import_dump(source).ok());
    auto before = store.current();

    // Truncate the payload by one byte: the header's length no longer matches.
    auto bytes_path = dir / "truncated.dump";
    fs::copy_file(source, bytes_path);
    fs::resize_file(bytes_path, fs::file_size(bytes_path) - 1);
    EXPECT_FALSE(store.import_dump(bytes_path).ok());
    EXPECT_EQ(store.current(), before);
}

}  // namespace
}  // namespace lc
