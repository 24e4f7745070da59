// What the loader reads for a material's textures beyond TEXCOORD_0:
// TEXCOORD_1 where a texture asks for it, KHR_texture_transform (scale,
// rotation, offset, texCoord override) applied to the mesh's uvs, COLOR_0,
// alphaMode / alphaCutoff / doubleSided and normalTexture.scale, and the
// effects report naming them.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <numbers>
#include <vector>

#include "editor_client/render/analysis/scene_effects.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/inputs/texture_coordinates.h"
#include "test_paths.h"

namespace lc::client {
namespace {

using json = nlohmann::json;

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

// A 1x1 white RGBA PNG.
constexpr const char* kWhitePng =
    "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGP4//8/AwAI/AL+"
    "XJ/PchAAAABJRU5ErkJggg==";

// One quad in z = 0 with two uv sets and vertex colours; `material` is its
// material; `tangents`: with NORMAL and TANGENT attributes too.
json quad_document(const json& material, bool tangents = false) {
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const std::vector<float> uv0 = {0, 1, 1, 1, 1, 0, 0, 0};
    const std::vector<float> uv1 = {0.5f, 0.5f, 0.75f, 0.5f, 0.75f, 0.25f, 0.5f, 0.25f};
    const std::vector<float> colors = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 0.5f, 1, 1, 1, 1};
    const std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3};
    std::vector<uint8_t> bin;
    json views = json::array(), accessors = json::array();
    auto add = [&](const void* data, size_t bytes, int component, size_t count, const char* type) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t offset = bin.size();
        bin.resize(offset + bytes);
        std::memcpy(bin.data() + offset, data, bytes);
        views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
        accessors.push_back({{"bufferView", views.size() - 1},
                             {"componentType", component},
                             {"count", count},
                             {"type", type}});
        return int(accessors.size() - 1);
    };
    json position = add(positions.data(), 48, 5126, 4, "VEC3");
    accessors[size_t(position.get<int>())]["min"] = {0, 0, 0};
    accessors[size_t(position.get<int>())]["max"] = {1, 1, 0};
    const json attributes = {{"POSITION", position},
                             {"TEXCOORD_0", add(uv0.data(), 32, 5126, 4, "VEC2")},
                             {"TEXCOORD_1", add(uv1.data(), 32, 5126, 4, "VEC2")},
                             {"COLOR_0", add(colors.data(), 64, 5126, 4, "VEC4")}};
    json with = attributes;
    if (tangents) {
        const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
        const std::vector<float> along_x = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
        with["NORMAL"] = add(normals.data(), 48, 5126, 4, "VEC3");
        with["TANGENT"] = add(along_x.data(), 64, 5126, 4, "VEC4");
    }
    const int index_accessor = add(indices.data(), 12, 5123, 6, "SCALAR");
    json doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes",
         {{{"primitives", {{{"attributes", with}, {"indices", index_accessor}, {"material", 0}}}}}}},
        {"materials", {material}},
        {"images", {{{"uri", kWhitePng}}}},
        {"textures", {{{"source", 0}}}},
        {"accessors", accessors},
        {"bufferViews", views},
        {"buffers",
         {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}}},
        {"extensionsUsed", {"KHR_texture_transform"}}};
    return doc;
}

Scene load(const json& doc, std::vector<std::string>& warnings) {
    const std::filesystem::path dir = test::make_temp_dir("texture_inputs");
    std::ofstream(dir / "quad.gltf") << doc.dump(1);
    Result<Scene> scene = load_scene(dir / "quad.gltf", warnings);
    EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error());
    return scene.ok() ? std::move(scene).value() : Scene{};
}

TEST(TextureInputs, TransformScalesRotatesCounterClockwiseThenOffsets) {
    TextureCoordinates c;
    c.transformed = true;
    c.offset = {0.0f, 1.0f};
    c.rotation = float(std::numbers::pi / 2.0);
    c.scale = {0.5f, 0.5f};
    // The extension's example: the lower left quadrant, turned clockwise.
    const glm::vec2 a = transform_uv(c, {1.0f, 0.0f}), b = transform_uv(c, {0.0f, 1.0f});
    EXPECT_NEAR(a.x, 0.0f, 1e-6f);
    EXPECT_NEAR(a.y, 0.5f, 1e-6f);
    EXPECT_NEAR(b.x, 0.5f, 1e-6f);
    EXPECT_NEAR(b.y, 1.0f, 1e-6f);
    EXPECT_EQ(transform_uv(TextureCoordinates{}, {0.3f, 0.7f}), glm::vec2(0.3f, 0.7f));
}

TEST(TextureInputs, TexCoordOneTransformAndVertexColoursAreRead) {
    const json material = {
        {"pbrMetallicRoughness",
         {{"baseColorTexture",
           {{"index", 0},
            {"texCoord", 1},
            {"extensions", {{"KHR_texture_transform", {{"offset", {0.25, 0.0}}, {"scale", {2.0, 2.0}}}}}}}}}},
        {"alphaMode", "MASK"},
        {"alphaCutoff", 0.3},
        {"doubleSided", true},
        {"normalTexture",
         {{"index", 0},
          {"texCoord", 1},
          {"scale", 0.5},
          {"extensions", {{"KHR_texture_transform", {{"offset", {0.25, 0.0}}, {"scale", {2.0, 2.0}}}}}}}}};
    std::vector<std::string> warnings;
    const Scene scene = load(quad_document(material), warnings);
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    // TEXCOORD_1 (0.5, 0.5) scaled by 2 and offset by (0.25, 0): (1.25, 1).
    ASSERT_EQ(mesh.uvs.size(), 4u);
    EXPECT_NEAR(mesh.uvs[0].x, 1.25f, 1e-6f);
    EXPECT_NEAR(mesh.uvs[0].y, 1.0f, 1e-6f);
    ASSERT_EQ(mesh.colors.size(), 4u);
    EXPECT_EQ(mesh.colors[2], glm::vec4(0, 0, 1, 0.5f));
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.alpha_mode, AlphaMode::kMask);
    EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.3f);
    EXPECT_TRUE(m.double_sided);
    EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
    EXPECT_EQ(m.texture_coordinates.set, 1);
    EXPECT_EQ(mesh.tangents.size(), 4u);  // generated: the file has no TANGENT
    for (const std::string& w : warnings) ADD_FAILURE() << "unexpected warning: " << w;
    // The normal map asks for another set: sampled with the base colour's
    // coordinates, with a warning.
    json other = material;
    other["normalTexture"]["texCoord"] = 0;
    std::vector<std::string> other_warnings;
    load(quad_document(other), other_warnings);
    ASSERT_EQ(other_warnings.size(), 1u);
    EXPECT_NE(other_warnings[0].find("normalTexture"), std::string::npos) << other_warnings[0];

    const SceneEffects effects = analyse_scene_effects(scene, nullptr);
    int named = 0;
    for (const EffectDecision& d : effects.decisions) {
        if (d.name.find("TEXCOORD_1") != std::string::npos || d.name.find("COLOR_0") != std::string::npos ||
            d.name.find("normalTexture") != std::string::npos ||
            d.name.find("alphaMode MASK") != std::string::npos) {
            EXPECT_TRUE(d.simulated) << d.name << ": " << d.reason;
            ++named;
        }
    }
    EXPECT_EQ(named, 4);
}

// A material whose only texture is its normal map turns textures on (the
// G-buffer samples normal maps only with them), with the file's TANGENT or
// generated ones, and the report names the normal texture.
TEST(TextureInputs, ANormalTextureAloneTurnsNormalMappingOn) {
    const json material = {{"normalTexture", {{"index", 0}}}};
    for (bool tangents : {false, true}) {
        std::vector<std::string> warnings;
        const Scene scene = load(quad_document(material, tangents), warnings);
        ASSERT_EQ(scene.meshes.size(), 1u);
        ASSERT_EQ(scene.meshes[0].tangents.size(), 4u) << "TANGENT " << tangents;
        const SceneEffects effects = analyse_scene_effects(scene, nullptr);
        EXPECT_TRUE(effects.textures) << "TANGENT " << tangents;
        bool reported = false;
        for (const EffectDecision& d : effects.decisions) {
            if (d.name.find("normal textures") == std::string::npos) continue;
            reported = true;
            EXPECT_TRUE(d.simulated);
            EXPECT_EQ(d.reason, "drawn materials sample normal textures");
        }
        EXPECT_TRUE(reported);
    }
    // Without texture coordinates nothing can be sampled.
    json bare = quad_document(material);
    bare["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
    bare["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_1");
    std::vector<std::string> warnings;
    EXPECT_FALSE(analyse_scene_effects(load(bare, warnings), nullptr).textures);
}

TEST(TextureInputs, TexCoordOverrideAndBadTransformsAreHandled) {
    json material = {{"pbrMetallicRoughness",
                      {{"baseColorTexture",
                        {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}}}}}};
    std::vector<std::string> warnings;
    Scene scene = load(quad_document(material), warnings);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].uvs[1], glm::vec2(0.75f, 0.5f));  // TEXCOORD_1 as it is
    material["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 3;
    material["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = json::object();
    warnings.clear();
    scene = load(quad_document(material), warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("TEXCOORD_3"), std::string::npos);
    EXPECT_EQ(scene.meshes[0].uvs[1], glm::vec2(1.0f, 1.0f));  // TEXCOORD_0
}

}  // namespace
}  // namespace lc::client
