// The glTF writer: whole scenes round-trip through the loader, and rewriting
// the lights of an existing file keeps everything else.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "test_paths.h"

namespace lc::client {
namespace {

using json = nlohmann::json;
using ::testing::HasSubstr;

json read_json(const std::filesystem::path& path) {
    std::ifstream in(path);
    return json::parse(in);
}

void expect_vec_near(const glm::vec3& a, const glm::vec3& b, float eps) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

SceneLight light(LightType type, glm::vec3 position, glm::vec3 direction, uint32_t id) {
    SceneLight l;
    l.guid = Guid{0xABCD0000u, 1, 2, id};
    l.type = type;
    l.position = position;
    l.direction = glm::normalize(direction);
    return l;
}

// Every field the writer promises to keep.
Scene sample_scene() {
    Scene s;
    Mesh quad;
    quad.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
    quad.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 2, 1, 0, 3, 2};
    quad.material = 1;
    Mesh tri;
    tri.positions = {{0, 1, 0}, {0.5f, 2, 0.25f}, {-0.3f, 1.5f, 0.7f}};
    tri.normals = {glm::normalize(glm::vec3(1, 1, 0)), {0, 0, 1}, {1, 0, 0}};
    tri.indices = {0, 1, 2};
    s.meshes = {quad, tri};
    Material grey;
    grey.base_color_factor = {0.5f, 0.5f, 0.5f, 1.0f};
    grey.metallic = 0.0f;
    grey.roughness = 0.8f;
    Material glow;
    glow.emissive_factor = {6.0f, 3.0f, 0.0f};  // beyond 1: needs emissive_strength
    s.materials = {grey, glow};
    Camera camera;
    camera.name = "main";
    camera.eye = {0, 3, 6};
    camera.target = {0, 0.5f, 0};
    camera.yfov = 0.9f;
    s.cameras = {camera};
    SceneLight point = light(LightType::kPoint, {0.25f, 1.5f, -0.5f}, {0, 0, -1}, 1);
    point.color = {1.0f, 0.5f, 0.25f};
    point.intensity = 12.5f;
    point.range = 3.0f;
    SceneLight spot = light(LightType::kSpot, {1, 2, 1}, {0.2f, -1, 0.1f}, 2);
    spot.inner_cone_angle = 0.2f;
    spot.outer_cone_angle = 0.7f;
    spot.classic = true;
    SceneLight sun = light(LightType::kDirectional, {0, 0, 0}, {0, 0, 1}, 3);  // opposite -Z
    sun.intensity = 2.0f;
    s.lights = {point, spot, sun};
    update_scene_bounds(s);
    return s;
}

class GltfWriter : public ::testing::Test {
protected:
    void SetUp() override { dir_ = lc::test::make_temp_dir("gltf-writer"); }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    void expect_same_scene(const Scene& a, const Scene& b) {
        ASSERT_EQ(a.meshes.size(), b.meshes.size());
        for (size_t m = 0; m < a.meshes.size(); ++m) {
            EXPECT_EQ(a.meshes[m].positions, b.meshes[m].positions);
            EXPECT_EQ(a.meshes[m].uvs, b.meshes[m].uvs);
            EXPECT_EQ(a.meshes[m].indices, b.meshes[m].indices);
            EXPECT_EQ(a.meshes[m].material, b.meshes[m].material);
            ASSERT_EQ(a.meshes[m].normals.size(), b.meshes[m].normals.size());
            for (size_t i = 0; i < a.meshes[m].normals.size(); ++i)
                expect_vec_near(a.meshes[m].normals[i], b.meshes[m].normals[i], 1e-6f);
        }
        ASSERT_EQ(a.materials.size(), b.materials.size());
        for (size_t i = 0; i < a.materials.size(); ++i) {
            EXPECT_EQ(a.materials[i].base_color_factor, b.materials[i].base_color_factor);
            EXPECT_EQ(a.materials[i].metallic, b.materials[i].metallic);
            EXPECT_EQ(a.materials[i].roughness, b.materials[i].roughness);
            expect_vec_near(a.materials[i].emissive_factor, b.materials[i].emissive_factor, 1e-5f);
        }
        ASSERT_EQ(a.cameras.size(), b.cameras.size());
        for (size_t i = 0; i < a.cameras.size(); ++i) {
            EXPECT_EQ(a.cameras[i].name, b.cameras[i].name);
            EXPECT_EQ(a.cameras[i].eye, b.cameras[i].eye);
            EXPECT_FLOAT_EQ(a.cameras[i].yfov, b.cameras[i].yfov);
            expect_vec_near(glm::normalize(a.cameras[i].target - a.cameras[i].eye),
                            glm::normalize(b.cameras[i].target - b.cameras[i].eye), 1e-6f);
        }
        expect_same_lights(a.lights, b.lights);
    }

    void expect_same_lights(const std::vector<SceneLight>& a, const std::vector<SceneLight>& b) {
        ASSERT_EQ(a.size(), b.size());
        for (size_t i = 0; i < a.size(); ++i) {
            EXPECT_EQ(a[i].guid, b[i].guid) << "light " << i;
            EXPECT_EQ(a[i].type, b[i].type);
            EXPECT_EQ(a[i].position, b[i].position);
            expect_vec_near(a[i].direction, b[i].direction, 1e-6f);
            EXPECT_EQ(a[i].color, b[i].color);
            EXPECT_EQ(a[i].intensity, b[i].intensity);
            EXPECT_EQ(a[i].range, b[i].range);
            EXPECT_EQ(a[i].classic, b[i].classic);
            if (a[i].type == LightType::kSpot) {
                EXPECT_EQ(a[i].inner_cone_angle, b[i].inner_cone_angle);
                EXPECT_EQ(a[i].outer_cone_angle, b[i].outer_cone_angle);
            }
        }
    }

    std::filesystem::path dir_;
};

TEST_F(GltfWriter, WholeSceneRoundTripsThroughGltfAndGlb) {
    const Scene scene = sample_scene();
    for (const char* name : {"scene.gltf", "scene.glb"}) {
        SCOPED_TRACE(name);
        ASSERT_TRUE(write_scene_gltf(scene, dir_ / name).ok());
        Result<Scene> loaded = load_scene(dir_ / name);
        ASSERT_TRUE(loaded.ok()) << loaded.error();
        expect_same_scene(scene, *loaded);
        EXPECT_EQ(loaded->bounds_min, scene.bounds_min);
        EXPECT_EQ(loaded->bounds_max, scene.bounds_max);
    }
    // The .glb is binary; the .gltf embeds its buffer as base64 and declares the extensions.
    std::ifstream glb(dir_ / "scene.glb", std::ios::binary);
    char magic[4];
    glb.read(magic, 4);
    EXPECT_EQ(std::string(magic, 4), "glTF");
    const json doc = read_json(dir_ / "scene.gltf");
    EXPECT_THAT(doc["buffers"][0]["uri"].get<std::string>(),
                HasSubstr("data:application/octet-stream;base64,"));
    EXPECT_THAT(doc["extensionsUsed"].dump(), HasSubstr("KHR_lights_punctual"));
    EXPECT_THAT(doc["extensionsUsed"].dump(), HasSubstr("KHR_materials_emissive_strength"));
    EXPECT_EQ(doc["nodes"][3]["extras"]["lightcuts_guid"], sample_scene().lights[0].guid.to_hex());
    // Deterministic: writing again gives the same bytes.
    ASSERT_TRUE(write_scene_gltf(scene, dir_ / "again.gltf").ok());
    EXPECT_EQ(read_json(dir_ / "again.gltf"), doc);
}

std::string read_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The light nodes and lights are written an element at a time; the text is
// what nlohmann gives for the whole document (parsed and dumped again, it is
// the same bytes), .gltf and .glb, and also when a scene's own string spells
// the writer's placeholder (then the arrays are made whole first).
TEST_F(GltfWriter, StreamedLightsAreTheWholeDocumentsText) {
    Scene scene = sample_scene();
    for (uint32_t i = 0; i < 50; ++i) {
        scene.lights.push_back(light(i % 2 ? LightType::kSpot : LightType::kPoint,
                                     {0.1f * float(i), 1.0f, -0.3f}, {0.0f, -1.0f, 0.1f}, 100 + i));
    }
    Scene spelled = scene;
    spelled.cameras[0].name = "lightcuts-writer:lights";
    for (const Scene* written : {&scene, &spelled}) {
        ASSERT_TRUE(write_scene_gltf(*written, dir_ / "streamed.gltf").ok());
        const std::string text = read_bytes(dir_ / "streamed.gltf");
        const json doc = json::parse(text);
        EXPECT_EQ(doc.dump(2) + "\n", text);
        EXPECT_EQ(doc["extensions"]["KHR_lights_punctual"]["lights"].size(), written->lights.size());
        Result<Scene> loaded = load_scene(dir_ / "streamed.gltf");
        ASSERT_TRUE(loaded.ok()) << loaded.error();
        expect_same_scene(*written, *loaded);

        ASSERT_TRUE(write_scene_gltf(*written, dir_ / "streamed.glb").ok());
        const std::string glb = read_bytes(dir_ / "streamed.glb");
        ASSERT_GT(glb.size(), 20u);
        const uint32_t json_bytes = uint32_t(uint8_t(glb[12])) | uint32_t(uint8_t(glb[13])) << 8 |
                                    uint32_t(uint8_t(glb[14])) << 16 | uint32_t(uint8_t(glb[15])) << 24;
        std::string chunk = glb.substr(20, json_bytes);
        while (!chunk.empty() && chunk.back() == ' ') chunk.pop_back();
        EXPECT_EQ(json::parse(chunk).dump(), chunk);
        // The same document but for the buffer, embedded in the .gltf only.
        EXPECT_EQ(json::parse(chunk)["nodes"], doc["nodes"]);
        EXPECT_EQ(json::parse(chunk)["extensions"], doc["extensions"]);
    }
}

TEST_F(GltfWriter, RejectsInvalidLightsAndMissingFolders) {
    Scene scene = sample_scene();
    scene.lights[1].position.y = std::numeric_limits<float>::quiet_NaN();
    Status status = write_scene_gltf(scene, dir_ / "bad.gltf");
    ASSERT_FALSE(status.ok());
    EXPECT_THAT(status.error(), HasSubstr("light 1"));
    EXPECT_THAT(status.error(), HasSubstr("position"));
    EXPECT_FALSE(std::filesystem::exists(dir_ / "bad.gltf"));

    // glTF has no cosine emitter: an oriented light (an area-light sample) is refused.
    scene = sample_scene();
    scene.lights[0].type = LightType::kOriented;
    status = write_scene_gltf(scene, dir_ / "bad.gltf");
    ASSERT_FALSE(status.ok());
    EXPECT_THAT(status.error(), HasSubstr("no oriented light type"));

    scene = sample_scene();
    scene.lights[0].intensity = -1.0f;
    status = write_scene_gltf(scene, dir_ / "bad.gltf");
    ASSERT_FALSE(status.ok());
    EXPECT_THAT(status.error(), HasSubstr("intensity"));

    status = write_scene_gltf(sample_scene(), dir_ / "no" / "such" / "folder.gltf");
    ASSERT_FALSE(status.ok());
    EXPECT_THAT(status.error(), HasSubstr("does not exist"));
}

TEST_F(GltfWriter, ReplacingLightsKeepsEverythingElse) {
    const Scene scene = sample_scene();
    ASSERT_TRUE(write_scene_gltf(scene, dir_ / "source.gltf").ok());
    std::vector<SceneLight> lights{light(LightType::kPoint, {3, 3, 3}, {0, 0, -1}, 10),
                                   light(LightType::kSpot, {-1, 2, 0}, {0, -1, 0}, 11),
                                   light(LightType::kPoint, {0, 4, 0}, {0, 0, -1}, 12),
                                   light(LightType::kPoint, {1, 4, 0}, {0, 0, -1}, 13)};
    ASSERT_TRUE(write_lights_into_gltf(dir_ / "source.gltf", lights, dir_ / "more.gltf").ok());
    Result<Scene> more = load_scene(dir_ / "more.gltf");
    ASSERT_TRUE(more.ok()) << more.error();
    Scene expected = scene;
    expected.lights = lights;
    expect_same_scene(expected, *more);
    // The three light nodes were reused and one was appended.
    const json source_doc = read_json(dir_ / "source.gltf");
    const json more_doc = read_json(dir_ / "more.gltf");
    EXPECT_EQ(more_doc["nodes"].size(), source_doc["nodes"].size() + 1);
    for (const char* key :
         {"meshes", "accessors", "bufferViews", "buffers", "materials", "cameras"})
        EXPECT_EQ(more_doc[key], source_doc[key]) << key;

    // Fewer lights: trailing light nodes are dropped, the extension stays.
    ASSERT_TRUE(
        write_lights_into_gltf(dir_ / "more.gltf", std::span(lights).first(1), dir_ / "one.gltf")
            .ok());
    Result<Scene> one = load_scene(dir_ / "one.gltf");
    ASSERT_TRUE(one.ok()) << one.error();
    expect_same_lights(std::vector<SceneLight>(lights.begin(), lights.begin() + 1), one->lights);
    EXPECT_EQ(read_json(dir_ / "one.gltf")["nodes"].size(), source_doc["nodes"].size() - 2);

    // No lights: the extension disappears entirely.
    ASSERT_TRUE(write_lights_into_gltf(dir_ / "one.gltf", {}, dir_ / "none.gltf").ok());
    const json none_doc = read_json(dir_ / "none.gltf");
    EXPECT_FALSE(none_doc.contains("extensions") &&
                 none_doc["extensions"].contains("KHR_lights_punctual"));
    EXPECT_THAT(none_doc["extensionsUsed"].dump(),
                ::testing::Not(HasSubstr("KHR_lights_punctual")));
    Result<Scene> none = load_scene(dir_ / "none.gltf");
    ASSERT_TRUE(none.ok()) << none.error();
    EXPECT_TRUE(none->lights.empty());
    EXPECT_EQ(none->meshes.size(), scene.meshes.size());
}

TEST_F(GltfWriter, GlbSourcesBecomeSelfContainedGltf) {
    const Scene scene = sample_scene();
    ASSERT_TRUE(write_scene_gltf(scene, dir_ / "source.glb").ok());
    ASSERT_TRUE(write_lights_into_gltf(dir_ / "source.glb", scene.lights, dir_ / "copy.gltf").ok());
    ASSERT_TRUE(write_lights_into_gltf(dir_ / "source.glb", scene.lights, dir_ / "copy.glb").ok());
    for (const char* name : {"copy.gltf", "copy.glb"}) {
        SCOPED_TRACE(name);
        Result<Scene> loaded = load_scene(dir_ / name);
        ASSERT_TRUE(loaded.ok()) << loaded.error();
        expect_same_scene(scene, *loaded);
    }
}

TEST_F(GltfWriter, ExternalFilesAreFoundFromAnotherFolder) {
    LC_REQUIRE_SHARED_SCENES();
    const auto source =
        lc::test::shared_scenes_dir() / "LightsPunctualLamp" / "LightsPunctualLamp.gltf";
    Result<Scene> original = load_scene(source);
    ASSERT_TRUE(original.ok()) << original.error();
    // Keep the lamp's lights (their GUIDs must survive) and add one.
    std::vector<SceneLight> lights = original->lights;
    lights.push_back(light(LightType::kPoint, {0, 2, 0}, {0, 0, -1}, 99));
    ASSERT_TRUE(write_lights_into_gltf(source, lights, dir_ / "lamp.gltf").ok());
    // Its URIs lead out of its own folder: read only when allowed.
    Result<Scene> refused = load_scene(dir_ / "lamp.gltf");
    ASSERT_FALSE(refused.ok());
    EXPECT_THAT(refused.error(), HasSubstr("--allow-external-resources"));
    Result<Scene> edited =
        load_scene(dir_ / "lamp.gltf", GltfLoadOptions{.allow_external_resources = true});
    ASSERT_TRUE(edited.ok()) << edited.error();
    ASSERT_EQ(edited->lights.size(), 6u);
    expect_same_lights(lights, edited->lights);
    ASSERT_EQ(edited->meshes.size(), original->meshes.size());
    for (size_t m = 0; m < edited->meshes.size(); ++m)
        EXPECT_EQ(edited->meshes[m].positions, original->meshes[m].positions);
    // Textures still load: the image URIs now lead back to the lamp's folder.
    ASSERT_EQ(edited->textures.size(), original->textures.size());
    for (size_t t = 0; t < edited->textures.size(); ++t)
        EXPECT_EQ(edited->textures[t].rgba8, original->textures[t].rgba8);
    const json doc = read_json(dir_ / "lamp.gltf");
    EXPECT_THAT(doc["extensionsUsed"].dump(), HasSubstr("KHR_materials_transmission"));
    EXPECT_THAT(doc["images"][0]["uri"].get<std::string>(), HasSubstr("LightsPunctualLamp/"));
}

}  // namespace
}  // namespace lc::client
