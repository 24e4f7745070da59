// The fast path of glTF import (gltf_node_reader.h): it takes the files our
// writer makes, gives the scene tinygltf gives on every input (generated
// scenes, every broken file, unusual forms it leaves to tinygltf), and is
// deterministic.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "editor_client/scene/gltf/gltf_node_reader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "gltf_import_equivalence.h"
#include "test_paths.h"

namespace lc::client {
namespace {

using json = nlohmann::json;
using lc::test::load_scene_both_ways;

std::optional<GltfNodeSplit> read_nodes(const std::string& bytes,
                                        const ConsumedBytes& on_consumed = {}) {
    return read_gltf_nodes({reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()},
                           on_consumed);
}

// Every named scene, and the room with a thousand lights of every type, some
// classic and some with a range.
std::vector<Scene> generated_scenes() {
    std::vector<Scene> scenes;
    for (const std::string& name : named_scene_names()) {
        Result<Scene> scene = make_named_scene(name);
        EXPECT_TRUE(scene.ok()) << name;
        if (scene.ok()) scenes.push_back(std::move(*scene));
    }
    Scene room = make_room_scene();
    for (int variant = 0; variant < 2; ++variant) {
        LightLayoutOptions layout;
        layout.count = 500;
        layout.type = LightTypeChoice::kMixed;
        layout.seed = uint64_t(variant) + 7;
        layout.classic = variant == 1;
        layout.range = variant == 1 ? 3.0f : 0.0f;
        layout.box_min = glm::vec3(-2.0f, 0.5f, -2.0f);
        layout.box_max = glm::vec3(2.0f, 2.5f, 2.0f);
        Result<std::vector<SceneLight>> lights = generate_lights(layout);
        EXPECT_TRUE(lights.ok());
        if (lights.ok()) room.lights.insert(room.lights.end(), lights->begin(), lights->end());
    }
    scenes.push_back(std::move(room));
    return scenes;
}

class GltfNodeReader : public ::testing::Test {
protected:
    void SetUp() override { dir_ = lc::test::make_temp_dir("gltf-node-reader"); }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path dir_;
};

TEST_F(GltfNodeReader, GeneratedScenesTakeTheFastPathAndLoadAsWithTinygltf) {
    const std::vector<Scene> scenes = generated_scenes();
    ASSERT_GE(scenes.size(), 2u);
    for (size_t i = 0; i < 2 * scenes.size(); ++i) {
        const auto path =
            dir_ / ("scene" + std::to_string(i) + (i < scenes.size() ? ".gltf" : ".glb"));
        const Scene& written = scenes[i % scenes.size()];
        ASSERT_TRUE(write_scene_gltf(written, path).ok());
        const std::optional<GltfNodeSplit> split = read_nodes(test::read_text(path));
        ASSERT_TRUE(split.has_value()) << path << " fell back to tinygltf";
        EXPECT_EQ(split->table.lights.size(), written.lights.size());
        EXPECT_EQ(split->remainder.find("lightcuts_guid"), std::string::npos);
        Result<Scene> scene = load_scene_both_ways(path);
        ASSERT_TRUE(scene.ok()) << scene.error();
        EXPECT_EQ(scene->lights.size(), written.lights.size());
    }
}

TEST_F(GltfNodeReader, EveryBrokenFileFailsAsWithTinygltf) {
    int failed = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(lc::test::data_dir() / "broken_gltf")) {
        const std::string ext = entry.path().extension().string();
        if (ext != ".gltf" && ext != ".glb") continue;
        std::vector<std::string> warnings;
        failed += load_scene_both_ways(entry.path(), warnings).ok() ? 0 : 1;
    }
    EXPECT_GE(failed, 30);
}

// Forms the reader leaves to tinygltf: what tinygltf would ignore or bend
// (a float mesh index, an empty matrix beside a translation, an unknown field)
// and what the loader refuses. The load's outcome is tinygltf's either way.
TEST_F(GltfNodeReader, UnusualFormsFallBackToTinygltf) {
    const json base = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 1}}}}},
        {"nodes",
         {{{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
          {{"name", "n"}}}},
        {"extensions",
         {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 2}}}}}}}}};
    ASSERT_TRUE(read_nodes(base.dump()).has_value());

    std::vector<json> variants;
    auto with = [&](const char* pointer, json value) {
        json doc = base;
        doc[json::json_pointer(pointer)] = std::move(value);
        variants.push_back(doc);
    };
    with("/nodes/1/mesh", 1.0);
    with("/nodes/1/matrix", json::array());
    with("/nodes/1/skin", 0);
    with("/nodes/0/extensions/KHR_lights_punctual/light", -1);
    with("/nodes/0/extensions/KHR_lights_punctual/light", 1.5);
    with("/nodes/0/extras", {{"lightcuts_classic", "yes"}});
    with("/nodes/0/translation/0", "1");
    with("/extensions/KHR_lights_punctual/lights/0/type", "area");
    with("/extensions/KHR_lights_punctual/lights/0/spot", {{"outerConeAngle", 0.5}});
    with("/extensions/KHR_lights_punctual/lights/0/color", {1, 2});
    with("/scenes/0/nodes/1", 7);
    int failed = 0;
    for (size_t i = 0; i < variants.size(); ++i) {
        const auto path = dir_ / ("variant" + std::to_string(i) + ".gltf");
        std::ofstream(path) << variants[i].dump(1);
        std::vector<std::string> warnings;
        failed += load_scene_both_ways(path, warnings).ok() ? 0 : 1;
    }
    // Refused by the loader: the light indices -1 and 1.5, the type, the
    // colour and the scene's missing node; the rest load as tinygltf bends them.
    EXPECT_EQ(failed, 5);
    // An integer "-0" is +0 to tinygltf's JSON and to the reader.
    std::string negative_zero = base.dump();
    negative_zero.replace(negative_zero.find("[1,2,3]"), 7, "[-0,2,-0.0]");
    const auto path = dir_ / "negative_zero.gltf";
    std::ofstream(path) << negative_zero;
    ASSERT_TRUE(read_nodes(negative_zero).has_value());
    Result<Scene> scene = load_scene_both_ways(path);
    ASSERT_TRUE(scene.ok()) << scene.error();
}

// A file of several megabytes is read a run of elements at a time (the
// parser never indexes it whole): the same lights as tinygltf, and the file's
// bytes released front to back as the reader goes, .gltf and .glb.
TEST_F(GltfNodeReader, LargeFilesAreReadInRunsWithTheSameLights) {
    Scene room = make_room_scene();
    LightLayoutOptions layout;
    layout.count = 12000;
    layout.type = LightTypeChoice::kMixed;
    layout.seed = 11;
    layout.box_min = glm::vec3(-2.0f, 0.5f, -2.0f);
    layout.box_max = glm::vec3(2.0f, 2.5f, 2.0f);
    Result<std::vector<SceneLight>> lights = generate_lights(layout);
    ASSERT_TRUE(lights.ok());
    room.lights = std::move(*lights);
    for (const char* extension : {".gltf", ".glb"}) {
        const auto path = dir_ / (std::string("large") + extension);
        ASSERT_TRUE(write_scene_gltf(room, path).ok());
        const std::string bytes = test::read_text(path);
        ASSERT_GT(bytes.size(), size_t{3} << 20) << "too small to take several runs";
        std::vector<size_t> consumed;
        const std::optional<GltfNodeSplit> split =
            read_nodes(bytes, [&](size_t offset) { consumed.push_back(offset); });
        ASSERT_TRUE(split.has_value()) << path << " fell back to tinygltf";
        EXPECT_EQ(split->table.lights.size(), room.lights.size());
        ASSERT_GE(consumed.size(), 3u) << path;
        EXPECT_TRUE(std::is_sorted(consumed.begin(), consumed.end()));
        EXPECT_LE(consumed.back(), bytes.size());
        Result<Scene> scene = load_scene_both_ways(path);
        ASSERT_TRUE(scene.ok()) << scene.error();
        EXPECT_EQ(scene->lights.size(), room.lights.size());
    }
}

TEST_F(GltfNodeReader, IsDeterministic) {
    const std::vector<Scene> scenes = generated_scenes();
    const auto path = dir_ / "room.gltf";
    ASSERT_TRUE(write_scene_gltf(scenes.back(), path).ok());
    const std::string text = test::read_text(path);
    const std::optional<GltfNodeSplit> first = read_nodes(text);
    const std::optional<GltfNodeSplit> second = read_nodes(text);
    ASSERT_TRUE(first && second);
    EXPECT_EQ(first->remainder, second->remainder);
    EXPECT_TRUE(lc::test::same_bits(first->table.numbers, second->table.numbers));
    EXPECT_EQ(first->table.children, second->table.children);
    EXPECT_EQ(first->table.text, second->table.text);
    ASSERT_EQ(first->table.nodes.size(), second->table.nodes.size());
    Result<Scene> a = load_scene(path);
    Result<Scene> b = load_scene(path);
    ASSERT_TRUE(a.ok() && b.ok());
    lc::test::expect_same_scene(*a, *b);
}

}  // namespace
}  // namespace lc::client
