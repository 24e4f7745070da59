// The glTF loader: transforms, attributes, materials, cameras, lights, the
// shared scenes, and one broken file per rule with its error message. Every
// file is loaded both ways (gltf_import_equivalence.h): the fast node reader
// must give tinygltf's scene, errors and warnings.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "editor_client/scene/inputs/scene_guid.h"
#include "gltf_import_equivalence.h"
#include "test_paths.h"

namespace lc::client {
namespace {

using json = nlohmann::json;
using ::testing::HasSubstr;
using lc::test::load_scene_both_ways;

std::string base64(const std::vector<uint8_t>& bytes) {
    static constexpr char k[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= bytes[i + 2];
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? k[v & 63] : '=';
    }
    return out;
}

// A 2x1 RGBA PNG: (255, 0, 0, 255) then (0, 128, 255, 64).
constexpr const char* kTinyPng =
    "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAYAAAD0In+KAAAAEUlEQVR4nGP4z8Dwn6Hhv"
    "wMAELoDvkeWIKAAAAAASUVORK5CYII=";

// Builds small glTF documents with one embedded buffer.
class GltfBuilder {
public:
    GltfBuilder() {
        doc["asset"] = {{"version", "2.0"}};
        doc["scene"] = 0;
        doc["scenes"] = json::array({json::object({{"nodes", json::array()}})});
        doc["nodes"] = json::array();
        doc["meshes"] = json::array();
        doc["accessors"] = json::array();
        doc["bufferViews"] = json::array();
    }
    int add_vec(const std::vector<float>& values, const char* type) {
        return add_accessor(values.data(), values.size() * sizeof(float), 5126,
                            values.size() / (std::string(type) == "VEC2" ? 2 : 3), type);
    }
    int add_indices(const std::vector<uint16_t>& values) {
        return add_accessor(values.data(), values.size() * 2, 5123, values.size(), "SCALAR");
    }
    int add_node(json node, int parent = -1) {
        doc["nodes"].push_back(std::move(node));
        const int index = int(doc["nodes"].size() - 1);
        if (parent < 0) {
            doc["scenes"][0]["nodes"].push_back(index);
        } else {
            doc["nodes"][size_t(parent)]["children"].push_back(index);
        }
        return index;
    }
    int add_mesh(json primitive) {
        doc["meshes"].push_back({{"primitives", json::array({std::move(primitive)})}});
        return int(doc["meshes"].size() - 1);
    }
    int add_light(json light) {
        doc["extensions"]["KHR_lights_punctual"]["lights"].push_back(std::move(light));
        return int(doc["extensions"]["KHR_lights_punctual"]["lights"].size() - 1);
    }
    std::filesystem::path write(const std::filesystem::path& path) {
        json out = doc;
        if (!bin.empty()) {
            out["buffers"] =
                json::array({{{"byteLength", bin.size()},
                              {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
        }
        for (const char* key : {"meshes", "accessors", "bufferViews"})
            if (out[key].empty()) out.erase(key);
        std::ofstream(path) << out.dump(1);
        return path;
    }
    json doc;

private:
    int add_accessor(const void* data, size_t bytes, int component, size_t count,
                     const char* type) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t offset = bin.size();
        bin.resize(offset + bytes);
        std::memcpy(bin.data() + offset, data, bytes);
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
        doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                    {"componentType", component},
                                    {"count", count},
                                    {"type", type}});
        return int(doc["accessors"].size() - 1);
    }
    std::vector<uint8_t> bin;
};

void expect_vec_near(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

// --- Transforms, attributes, materials, cameras, lights ---------------------------

class GltfLoaderScene : public ::testing::Test {
protected:
    void SetUp() override { dir_ = lc::test::make_temp_dir("gltf-loader"); }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path dir_;
};

TEST_F(GltfLoaderScene, FlattensTheHierarchyWithTrsAndMatrices) {
    GltfBuilder b;
    const int positions = b.add_vec({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int tri = b.add_mesh({{"attributes", {{"POSITION", positions}}}});  // non-indexed
    // Root: T(10,0,0) R_y(90 deg) S(2); child: matrix T(0,0,1) with the triangle.
    const double h = std::sqrt(0.5);
    const int root =
        b.add_node({{"translation", {10, 0, 0}}, {"rotation", {0, h, 0, h}}, {"scale", {2, 2, 2}}});
    b.add_node({{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1}}, {"mesh", tri}}, root);
    const int spot = b.add_light({{"type", "spot"}, {"spot", json::object()}, {"intensity", 7}});
    b.add_node({{"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}}, root);
    Result<Scene> scene = load_scene_both_ways(b.write(dir_ / "hierarchy.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->meshes.size(), 1u);
    const Mesh& mesh = scene->meshes[0];
    // p -> T R S (p + (0,0,1)); R_y(90): (x, y, z) -> (z, y, -x).
    expect_vec_near(mesh.positions[0], {12, 0, 0});
    expect_vec_near(mesh.positions[1], {12, 0, -2});
    expect_vec_near(mesh.positions[2], {12, 2, 0});
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
    // No normals in the file: generated from the world-space triangle (+Z rotated to +X).
    for (const glm::vec3& n : mesh.normals) expect_vec_near(n, {1, 0, 0});
    EXPECT_TRUE(mesh.uvs.empty());
    EXPECT_EQ(mesh.material, -1);

    ASSERT_EQ(scene->lights.size(), 1u);
    const SceneLight& light = scene->lights[0];
    EXPECT_EQ(light.type, LightType::kSpot);
    expect_vec_near(light.position, {10, 0, 0});
    expect_vec_near(light.direction, {-1, 0, 0});  // -Z rotated by R_y(90)
    EXPECT_EQ(light.color, glm::vec3(1.0f));       // colour defaults to white
    EXPECT_EQ(light.intensity, 7.0f);
    EXPECT_EQ(light.range, 0.0f);
    EXPECT_FLOAT_EQ(light.inner_cone_angle, 0.0f);  // spot defaults
    EXPECT_FLOAT_EQ(light.outer_cone_angle, float(std::numbers::pi / 4));
    EXPECT_FALSE(light.classic);
    expect_vec_near(scene->bounds_min, {10, 0, -2});
    expect_vec_near(scene->bounds_max, {12, 2, 0});
}

TEST_F(GltfLoaderScene, NormalsUseTheInverseTransposeAndMirrorsKeepWinding) {
    GltfBuilder b;
    const int positions = b.add_vec({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const float s = float(std::sqrt(0.5));
    const int normals = b.add_vec({s, s, 0, s, s, 0, s, s, 0}, "VEC3");
    const int uvs = b.add_vec({0, 0, 1, 0, 0, 1}, "VEC2");
    const int indices = b.add_indices({0, 1, 2});
    const int with_normals = b.add_mesh(
        {{"attributes", {{"POSITION", positions}, {"NORMAL", normals}, {"TEXCOORD_0", uvs}}},
         {"indices", indices}});
    const int without =
        b.add_mesh({{"attributes", {{"POSITION", positions}}}, {"indices", indices}});
    b.add_node({{"scale", {1, 4, 1}}, {"mesh", with_normals}});
    b.add_node({{"scale", {-1, 1, 1}}, {"mesh", without}});
    Result<Scene> scene = load_scene_both_ways(b.write(dir_ / "normals.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->meshes.size(), 2u);
    // Stretching y by 4 tilts the normal towards x: inverse transpose diag(1, 1/4, 1).
    for (const glm::vec3& n : scene->meshes[0].normals)
        expect_vec_near(n, glm::normalize(glm::vec3(1, 0.25f, 0)));
    EXPECT_EQ(scene->meshes[0].uvs.size(), 3u);
    EXPECT_EQ(scene->meshes[0].uvs[1], glm::vec2(1, 0));
    // A mirror flips the winding; the loader swaps two corners so the face stays front-facing,
    // and the generated normal still points to +Z.
    EXPECT_EQ(scene->meshes[1].indices, (std::vector<uint32_t>{0, 2, 1}));
    for (const glm::vec3& n : scene->meshes[1].normals) expect_vec_near(n, {0, 0, 1});
}

TEST_F(GltfLoaderScene, StripsAndFansBecomeTriangleLists) {
    GltfBuilder b;
    const int positions = b.add_vec({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", positions}}}, {"mode", 6}})}});
    b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", positions}}}, {"mode", 5}})}});
    b.add_node({{"mesh", b.add_mesh({{"attributes", {{"POSITION", positions}}}, {"mode", 1}})}});
    std::vector<std::string> warnings;
    Result<Scene> scene = load_scene_both_ways(b.write(dir_ / "modes.gltf"), warnings);
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->meshes.size(), 2u);  // the line primitive is skipped
    EXPECT_EQ(scene->meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));  // fan
    EXPECT_EQ(scene->meshes[1].indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));  // strip
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0], HasSubstr("mode 1"));
}

TEST_F(GltfLoaderScene, MaterialsTexturesAndEmission) {
    GltfBuilder b;
    const int positions = b.add_vec({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    b.doc["images"] = json::array({{{"uri", kTinyPng}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["materials"] = json::array(
        {{{"pbrMetallicRoughness",
           {{"baseColorFactor", {0.5, 0.25, 1, 1}},
            {"baseColorTexture", {{"index", 0}}},
            {"metallicFactor", 0.0},
            {"roughnessFactor", 0.75}}},
          {"emissiveFactor", {1, 0.5, 0}},
          {"emissiveTexture", {{"index", 0}}},
          {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}},
         json::object()});
    b.add_node(
        {{"mesh", b.add_mesh({{"attributes", {{"POSITION", positions}}}, {"material", 1}})}});
    Result<Scene> scene = load_scene_both_ways(b.write(dir_ / "materials.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->materials.size(), 2u);
    const Material& m = scene->materials[0];
    EXPECT_EQ(m.base_color_factor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
    EXPECT_EQ(m.metallic, 0.0f);
    EXPECT_EQ(m.roughness, 0.75f);
    EXPECT_EQ(m.emissive_factor, glm::vec3(4.0f, 2.0f, 0.0f));  // times emissiveStrength
    ASSERT_EQ(scene->textures.size(), 1u);                      // one image, shared by both slots
    EXPECT_EQ(m.base_color_texture, 0);
    EXPECT_EQ(m.emissive_texture, 0);
    const Texture& t = scene->textures[0];
    EXPECT_EQ(t.width, 2);
    EXPECT_EQ(t.height, 1);
    EXPECT_EQ(t.rgba8, (std::vector<uint8_t>{255, 0, 0, 255, 0, 128, 255, 64}));
    // The default material: glTF's defaults.
    const Material& d = scene->materials[1];
    EXPECT_EQ(d.base_color_factor, glm::vec4(1.0f));
    EXPECT_EQ(d.metallic, 1.0f);
    EXPECT_EQ(d.base_color_texture, -1);
    EXPECT_EQ(scene->meshes[0].material, 1);
}

TEST_F(GltfLoaderScene, CamerasLookDownTheirNodesMinusZ) {
    GltfBuilder b;
    b.doc["cameras"] =
        json::array({{{"type", "perspective"},
                      {"name", "front"},
                      {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}},
                     {{"type", "orthographic"},
                      {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 9}}}}});
    const double h = std::sqrt(0.5);
    b.add_node({{"camera", 0}, {"translation", {0, 1, 5}}});
    // Turned 90 degrees about Y: looks down -X.
    b.add_node({{"camera", 0}, {"translation", {3, 0, 0}}, {"rotation", {0, h, 0, h}}});
    b.add_node({{"camera", 1}});
    std::vector<std::string> warnings;
    Result<Scene> scene = load_scene_both_ways(b.write(dir_ / "cameras.gltf"), warnings);
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->cameras.size(), 2u);  // the orthographic one is skipped with a warning
    const Camera& c = scene->cameras[0];
    EXPECT_EQ(c.name, "front");
    expect_vec_near(c.eye, {0, 1, 5});
    expect_vec_near(glm::normalize(c.target - c.eye), {0, 0, -1});
    expect_vec_near(c.up, {0, 1, 0});
    EXPECT_FLOAT_EQ(c.yfov, 0.7f);
    expect_vec_near(glm::normalize(scene->cameras[1].target - scene->cameras[1].eye), {-1, 0, 0});
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0], HasSubstr("orthographic"));
}

TEST_F(GltfLoaderScene, LightTypesExtrasAndStableGuids) {
    GltfBuilder b;
    const int point = b.add_light({{"type", "point"},
                                   {"color", {1, 0.5, 0.25}},
                                   {"intensity", 20},
                                   {"range", 8},
                                   {"name", "bulb"}});
    const int sun =
        b.add_light({{"type", "directional"}, {"extras", {{"lightcuts_classic", true}}}});
    const int spot = b.add_light(
        {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.3}}}});
    auto ext = [](int light) { return json{{"KHR_lights_punctual", {{"light", light}}}}; };
    const int group = b.add_node({{"translation", {0, 5, 0}}});
    b.add_node({{"extensions", ext(point)}, {"translation", {1, 0, 0}}}, group);
    b.add_node({{"extensions", ext(point)}, {"translation", {-1, 0, 0}}}, group);  // instanced
    b.add_node({{"extensions", ext(sun)}, {"rotation", {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)}}});
    b.add_node(
        {{"extensions", ext(spot)},
         {"extras",
          {{"lightcuts_classic", true}, {"lightcuts_guid", "0123456789ABCDEF0123456789ABCDEF"}}}});
    const auto path = b.write(dir_ / "lights.gltf");
    Result<Scene> first = load_scene_both_ways(path);
    Result<Scene> second = load_scene_both_ways(path);
    ASSERT_TRUE(first.ok()) << first.error();
    ASSERT_TRUE(second.ok()) << second.error();
    const std::vector<SceneLight>& lights = first->lights;
    ASSERT_EQ(lights.size(), 4u);
    EXPECT_EQ(lights[0].type, LightType::kPoint);
    expect_vec_near(lights[0].position, {1, 5, 0});
    expect_vec_near(lights[1].position, {-1, 5, 0});
    EXPECT_EQ(lights[0].color, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(lights[0].intensity, 20.0f);
    EXPECT_EQ(lights[0].range, 8.0f);
    EXPECT_EQ(lights[2].type, LightType::kDirectional);
    expect_vec_near(lights[2].direction, {0, -1, 0});  // -Z turned -90 degrees about X
    EXPECT_TRUE(lights[2].classic);                    // from the light's extras
    EXPECT_TRUE(lights[3].classic);                    // from the node's extras
    EXPECT_FLOAT_EQ(lights[3].inner_cone_angle, 0.1f);
    EXPECT_FLOAT_EQ(lights[3].outer_cone_angle, 0.3f);
    EXPECT_EQ(lights[3].guid, *Guid::parse("0123456789ABCDEF0123456789ABCDEF"));
    // Derived GUIDs: stable across loads, distinct for one light on two nodes.
    for (size_t i = 0; i < lights.size(); ++i) {
        EXPECT_EQ(lights[i].guid, second->lights[i].guid);
        EXPECT_FALSE(lights[i].guid.is_zero());
    }
    EXPECT_NE(lights[0].guid, lights[1].guid);
    EXPECT_EQ(first->guid, second->guid);
    EXPECT_EQ(first->guid, compute_scene_guid(*first));
    // Directional lights have no position in the bounds.
    expect_vec_near(first->bounds_min, {-1, 0, 0});
    expect_vec_near(first->bounds_max, {1, 5, 0});

    // Another intensity: another scene GUID, same light GUIDs.
    b.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 21;
    Result<Scene> changed = load_scene_both_ways(b.write(dir_ / "lights.gltf"));
    ASSERT_TRUE(changed.ok()) << changed.error();
    EXPECT_NE(changed->guid, first->guid);
    EXPECT_EQ(changed->lights[0].guid, first->lights[0].guid);
}

TEST(SceneGuid, DependsOnGeometryAndLightsOnly) {
    Scene a;
    a.meshes.push_back(Mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, {0, 1, 2}, -1});
    a.lights.push_back(SceneLight{});
    Scene b = a;
    b.source = "elsewhere.gltf";
    b.materials.push_back(Material{});
    EXPECT_EQ(compute_scene_guid(a), compute_scene_guid(b));
    b.meshes[0].positions[2].y = 2.0f;
    EXPECT_NE(compute_scene_guid(a), compute_scene_guid(b));
    b = a;
    b.lights[0].classic = true;
    EXPECT_NE(compute_scene_guid(a), compute_scene_guid(b));
    b = a;
    b.lights[0].position.x = -0.0f;  // the same scene as +0
    EXPECT_EQ(compute_scene_guid(a), compute_scene_guid(b));
}

// --- The shared scenes -----------------------------------------------------------

TEST(GltfLoaderShared, LightsPunctualLampHasFivePointLights) {
    LC_REQUIRE_SHARED_SCENES();
    Result<Scene> scene = load_scene_both_ways(lc::test::shared_scenes_dir() / "LightsPunctualLamp" /
                                     "LightsPunctualLamp.gltf");
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->lights.size(), 5u);
    for (const SceneLight& l : scene->lights) {
        EXPECT_EQ(l.type, LightType::kPoint);
        EXPECT_EQ(l.range, 0.0f);
        EXPECT_FALSE(l.classic);
    }
    // Light 0: coloured, 15 cd, at the node's matrix translation.
    EXPECT_NEAR(scene->lights[0].color.y, 0.63187498f, 1e-6f);
    EXPECT_EQ(scene->lights[0].intensity, 15.0f);
    expect_vec_near(scene->lights[0].position, {0.04622355f, 0.90779734f, 0.00669663f});
    // Light 1 has no colour: white.
    EXPECT_EQ(scene->lights[1].color, glm::vec3(1.0f));
    EXPECT_EQ(scene->lights[1].intensity, 1.5f);
    EXPECT_EQ(scene->lights[4].intensity, 180.0f);
    ASSERT_EQ(scene->meshes.size(), 3u);
    for (const Mesh& m : scene->meshes) {
        EXPECT_FALSE(m.uvs.empty());
        EXPECT_EQ(m.normals.size(), m.positions.size());
        EXPECT_EQ(m.indices.size() % 3, 0u);
    }
    ASSERT_EQ(scene->materials.size(), 3u);
    EXPECT_GE(scene->materials[0].base_color_texture, 0);
    EXPECT_GE(scene->materials[0].emissive_texture, 0);
    for (const Texture& t : scene->textures) {
        EXPECT_GT(t.width, 0);
        EXPECT_EQ(t.rgba8.size(), size_t(t.width) * size_t(t.height) * 4);
    }
    EXPECT_TRUE(scene->cameras.empty());
    EXPECT_LT(scene->bounds_min.y, scene->bounds_max.y);
}

TEST(GltfLoaderShared, CornellBoxHasGeometryAndNoLights) {
    LC_REQUIRE_SHARED_SCENES();
    Result<Scene> scene =
        load_scene_both_ways(lc::test::shared_scenes_dir() / "cornell_box" / "cornell_box.gltf");
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_TRUE(scene->lights.empty());
    EXPECT_EQ(scene->meshes.size(), 8u);  // the front wall node has no mesh
    for (const Mesh& m : scene->meshes) {
        ASSERT_EQ(m.normals.size(), m.positions.size());  // generated: the file has none
        for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        EXPECT_TRUE(m.uvs.empty());
    }
    ASSERT_GE(scene->materials.size(), 5u);
    EXPECT_EQ(scene->materials[2].base_color_factor, glm::vec4(1, 0, 0, 1));  // "red"
    EXPECT_LT(scene->bounds_min.x, scene->bounds_max.x);
}

// --- Broken files ----------------------------------------------------------------

struct BrokenCase {
    const char* file;
    const char* message;  // a part of the expected error
};

class GltfLoaderBroken : public ::testing::TestWithParam<BrokenCase> {};

TEST_P(GltfLoaderBroken, FailsWithAMessageNamingTheProblem) {
    const BrokenCase& c = GetParam();
    const auto path = lc::test::data_dir() / "broken_gltf" / c.file;
    std::vector<std::string> warnings;
    Result<Scene> scene = load_scene_both_ways(path, warnings);
    ASSERT_FALSE(scene.ok()) << c.file << " loaded";
    EXPECT_THAT(scene.error(), HasSubstr(c.message)) << c.file;
    EXPECT_THAT(scene.error(), HasSubstr(c.file)) << "the message names the file";
}

INSTANTIATE_TEST_SUITE_P(
    AllRules, GltfLoaderBroken,
    ::testing::Values(
        BrokenCase{"no_such_file.gltf", "file does not exist"},
        BrokenCase{"empty.gltf", "the file is empty"}, BrokenCase{"bad_json.gltf", "invalid glTF"},
        BrokenCase{"truncated.glb", "invalid glTF binary"},
        BrokenCase{"missing_buffer_file.gltf", "no_such_buffer.bin"},
        BrokenCase{"short_buffer.gltf", "not as long as the buffer's byteLength"},
        BrokenCase{"short_buffer_file.gltf", "short.bin"},
        BrokenCase{"accessor_out_of_range.gltf",
                   "10 elements at offset 0 with stride 12 do not fit"},
        BrokenCase{"buffer_view_out_of_range.gltf", "lies outside buffer 0"},
        BrokenCase{"missing_buffer_view.gltf", "bufferView 7, which does not exist"},
        BrokenCase{"index_out_of_range.gltf",
                   "index 7 at element 2 is out of range of the 3 vertices"},
        BrokenCase{"nonfinite_position.gltf", "non-finite value at element 1"},
        BrokenCase{"vec2_positions.gltf",
                   "(mesh 0 primitive 0 POSITION) is VEC2 FLOAT, expected VEC3 FLOAT"},
        BrokenCase{"wrong_index_type.gltf", "is SCALAR FLOAT, expected SCALAR UNSIGNED_BYTE"},
        BrokenCase{"missing_accessor.gltf", "accessor 9, which does not exist"},
        BrokenCase{"recursive_nodes.gltf", "is its own ancestor"},
        BrokenCase{"self_child_node.gltf", "node 0 is its own child"},
        BrokenCase{"two_parents.gltf", "node 0 has two parents"},
        BrokenCase{"missing_child.gltf", "child 42, which does not exist"},
        BrokenCase{"missing_scene_node.gltf", "scene 0 lists node 5, which does not exist"},
        BrokenCase{"bad_scene_index.gltf", "'scene' is 3 but the file has 1 scenes"},
        BrokenCase{"missing_mesh.gltf", "mesh 4, which does not exist"},
        BrokenCase{"matrix_wrong_length.gltf", "'matrix' has 5 numbers, expected 16"},
        BrokenCase{"zero_rotation.gltf", "zero quaternion"},
        BrokenCase{"huge_translation.gltf", "is not finite"},
        BrokenCase{"negative_intensity.gltf", "light 0: negative intensity -2"},
        BrokenCase{"unknown_light_type.gltf", "unknown type 'area'"},
        BrokenCase{"bad_spot_angles.gltf", "invalid spot angles (inner 0.8, outer 0.5)"},
        BrokenCase{"spot_outer_too_wide.gltf", "need 0 <= inner < outer <= pi/2"},
        BrokenCase{"negative_color.gltf", "'color' components must be finite and >= 0"},
        BrokenCase{"negative_range.gltf", "range must be finite and > 0"},
        BrokenCase{"missing_light.gltf", "uses light 3, which does not exist"},
        BrokenCase{"light_without_index.gltf", "has no 'light' index"},
        BrokenCase{"directional_zero_scale.gltf", "collapses its direction"}),
    [](const ::testing::TestParamInfo<BrokenCase>& info) {
        std::string name = info.param.file;
        for (char& ch : name)
            if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
        return name;
    });

TEST(GltfLoaderBrokenBaseline, TheUnbrokenFileLoads) {
    Result<Scene> scene = load_scene_both_ways(lc::test::data_dir() / "broken_gltf" / "valid_triangle.gltf");
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_EQ(scene->meshes.size(), 1u);
    ASSERT_EQ(scene->lights.size(), 1u);
    expect_vec_near(scene->lights[0].position, {0, 0, 2});
}

TEST(GltfLoaderBrokenBaseline, NoSceneUsesEveryRootNode) {
    std::vector<std::string> warnings;
    Result<Scene> scene =
        load_scene_both_ways(lc::test::data_dir() / "broken_gltf" / "no_scene.gltf", warnings);
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_EQ(scene->meshes.size(), 1u);
    EXPECT_EQ(scene->lights.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0], HasSubstr("no scene"));
}

TEST(GltfLoaderBrokenBaseline, PointsAreSkippedWithAWarning) {
    std::vector<std::string> warnings;
    Result<Scene> scene =
        load_scene_both_ways(lc::test::data_dir() / "broken_gltf" / "points_primitive.gltf", warnings);
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_TRUE(scene->meshes.empty());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0], HasSubstr("points or lines"));
}

TEST(GltfLoaderBrokenBaseline, ADeepChainOfNodesLoadsWithoutRecursion) {
    // 50,000 nested nodes, each translating by 1 along x, the last holding a light.
    const auto dir = lc::test::make_temp_dir("gltf-chain");
    GltfBuilder b;
    int parent = -1;
    for (int i = 0; i < 50000; ++i) parent = b.add_node({{"translation", {1, 0, 0}}}, parent);
    b.add_light({{"type", "point"}});
    b.doc["nodes"][size_t(parent)]["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    Result<Scene> scene = load_scene_both_ways(b.write(dir / "chain.gltf"));
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->lights.size(), 1u);
    expect_vec_near(scene->lights[0].position, {50000, 0, 0});
    std::filesystem::remove_all(dir);
}

// Random corruptions of valid files (digits changed, bytes flipped, files cut
// short) must give a scene or an error message, never a crash. Run under
// LC_SANITIZE=ON this also checks that no byte outside a buffer is read.
TEST(GltfLoaderFuzz, RandomCorruptionsNeverCrash) {
    const auto dir = lc::test::make_temp_dir("gltf-fuzz");
    std::ifstream in(lc::test::data_dir() / "broken_gltf" / "valid_triangle.gltf");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Scene room = make_room_scene();
    SceneLight spot;
    spot.guid = Guid{1, 2, 3, 4};
    spot.type = LightType::kSpot;
    room.lights.push_back(spot);
    ASSERT_TRUE(write_scene_gltf(room, dir / "room.glb").ok());
    std::ifstream glb_in(dir / "room.glb", std::ios::binary);
    const std::string glb((std::istreambuf_iterator<char>(glb_in)), std::istreambuf_iterator<char>());

    std::mt19937_64 rng(12345);
    int loaded = 0, rejected = 0;
    for (int round = 0; round < 600; ++round) {
        const bool binary = round % 3 == 2;
        std::string bytes = binary ? glb : text;
        const int edits = 1 + int(rng() % 3);
        for (int e = 0; e < edits; ++e) {
            const size_t at = size_t(rng() % bytes.size());
            switch (rng() % 4) {
                case 0:  // a digit: indices, counts, offsets and lengths change
                    bytes[at] = char('0' + rng() % 10);
                    break;
                case 1: bytes[at] = char(rng() % 256); break;
                case 2: bytes.resize(at + 1); break;
                case 3: bytes.insert(at, binary ? std::string(1, char(rng() % 256)) : "9"); break;
            }
        }
        const auto path = dir / (binary ? "fuzz.glb" : "fuzz.gltf");
        std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
        std::vector<std::string> warnings;
        Result<Scene> scene = load_scene_both_ways(path, warnings);
        if (scene.ok()) {
            ++loaded;
            for (const Mesh& m : scene->meshes)
                for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
        } else {
            ++rejected;
            EXPECT_FALSE(scene.error().empty());
        }
    }
    RecordProperty("loaded", loaded);
    RecordProperty("rejected", rejected);
    EXPECT_GT(rejected, 100);  // the corruptions were real
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lc::client
