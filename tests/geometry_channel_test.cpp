// The geometry channel (protocol/geometry_channel.h): round trips in any
// chunking, per-face normals, degenerate triangles skipped and counted, and
// bad input refused with a message naming the record and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "protocol/geometry_channel.h"

namespace lc {
namespace {

SceneGeometry two_quads() {
    SceneGeometry g;
    SurfaceMaterial white;
    white.base_color = {0.73f, 0.73f, 0.73f};
    SurfaceMaterial panel;
    panel.emission = {17.0f, 12.0f, 4.0f};
    panel.roughness = 0.5f;
    g.materials = {white, panel};
    auto tri = [](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 n, uint32_t m) {
        SurfaceTriangle t;
        t.positions[0] = a;
        t.positions[1] = b;
        t.positions[2] = c;
        t.normals[0] = t.normals[1] = t.normals[2] = n;
        t.material = m;
        return t;
    };
    g.triangles = {tri({0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 1, 0}, 0),
                   tri({0, 0, 0}, {1, 0, 1}, {0, 0, 1}, {0, 1, 0}, 0),
                   tri({0, 2, 0}, {1, 2, 1}, {1, 2, 0}, {0, -1, 0}, 1)};
    return g;
}

void expect_same(const SceneGeometry& a, const SceneGeometry& b) {
    ASSERT_EQ(a.materials.size(), b.materials.size());
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        EXPECT_EQ(a.materials[i].base_color, b.materials[i].base_color);
        EXPECT_EQ(a.materials[i].emission, b.materials[i].emission);
        EXPECT_EQ(a.materials[i].metallic, b.materials[i].metallic);
        EXPECT_EQ(a.materials[i].roughness, b.materials[i].roughness);
    }
    for (size_t i = 0; i < a.triangles.size(); ++i) {
        for (int v = 0; v < 3; ++v) {
            EXPECT_EQ(a.triangles[i].positions[v], b.triangles[i].positions[v]);
            EXPECT_EQ(a.triangles[i].normals[v], b.triangles[i].normals[v]);
        }
        EXPECT_EQ(a.triangles[i].material, b.triangles[i].material);
    }
}

// Offset of a record field inside the encoded channel.
size_t material_offset(size_t index) { return 4 + index * geometry_material_record_bytes(); }
size_t triangle_offset(size_t materials, size_t index) {
    return material_offset(materials) + 4 + index * geometry_triangle_record_bytes();
}
void put_float(std::vector<uint8_t>& bytes, size_t offset, float value) {
    std::memcpy(&bytes[offset], &value, sizeof(float));
}

TEST(GeometryChannel, RoundTripsInAnyChunking) {
    const SceneGeometry g = two_quads();
    const std::vector<uint8_t> bytes = encode_geometry_channel(g);
    EXPECT_EQ(bytes.size(), geometry_channel_bytes(2, 3));
    Result<SceneGeometry> whole = decode_geometry_channel(bytes);
    ASSERT_TRUE(whole.ok()) << whole.error();
    expect_same(*whole, g);
    for (size_t chunk : {size_t(1), size_t(3), size_t(7), size_t(77)}) {
        GeometryChannelReader reader;
        for (size_t pos = 0; pos < bytes.size(); pos += chunk) {
            const size_t n = std::min(chunk, bytes.size() - pos);
            ASSERT_TRUE(reader.consume({bytes.data() + pos, n}).ok()) << "chunk " << chunk;
        }
        Result<SceneGeometry> streamed = reader.finish();
        ASSERT_TRUE(streamed.ok()) << streamed.error();
        expect_same(*streamed, g);
    }
}

TEST(GeometryChannel, EmptyGeometryAndPerFaceNormals) {
    Result<SceneGeometry> empty = decode_geometry_channel(encode_geometry_channel({}));
    ASSERT_TRUE(empty.ok()) << empty.error();
    EXPECT_TRUE(empty->triangles.empty());
    // All-zero normals ask for the face's normal (winding order: up for this one).
    SceneGeometry g = two_quads();
    for (glm::vec3& n : g.triangles[2].normals) n = glm::vec3(0.0f);
    Result<SceneGeometry> decoded = decode_geometry_channel(encode_geometry_channel(g));
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_EQ(decoded->triangles[2].normals[0], glm::vec3(0, 1, 0));
}

TEST(GeometryChannel, DegenerateTrianglesAreSkippedAndCounted) {
    SceneGeometry g = two_quads();
    SurfaceTriangle line = g.triangles[0];
    line.positions[2] = line.positions[1];
    g.triangles.insert(g.triangles.begin() + 1, {line, line});
    size_t skipped = 0;
    Result<SceneGeometry> decoded = decode_geometry_channel(encode_geometry_channel(g), &skipped);
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_EQ(skipped, 2u);
    expect_same(*decoded, two_quads());
    // Only degenerate triangles: an empty geometry, no failure.
    g.triangles = {line, line, line};
    decoded = decode_geometry_channel(encode_geometry_channel(g), &skipped);
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_TRUE(decoded->triangles.empty());
    EXPECT_EQ(skipped, 3u);
}

TEST(GeometryChannel, BadRecordsAreRefusedNamingTheField) {
    const std::vector<uint8_t> good = encode_geometry_channel(two_quads());
    auto refused = [&](std::vector<uint8_t> bytes, const std::string& expected) {
        Result<SceneGeometry> decoded = decode_geometry_channel(bytes);
        ASSERT_FALSE(decoded.ok()) << "expected: " << expected;
        EXPECT_NE(decoded.error().find(expected), std::string::npos) << decoded.error();
    };
    // Material 1's emission (after its 12-byte base colour).
    std::vector<uint8_t> bytes = good;
    put_float(bytes, material_offset(1) + 12, std::numeric_limits<float>::quiet_NaN());
    refused(bytes, "material 1: emission");
    bytes = good;
    put_float(bytes, material_offset(1) + 16, -1.0f);
    refused(bytes, "material 1: emission (17, -1, 4) is negative");
    bytes = good;
    put_float(bytes, material_offset(0), 1.5f);
    refused(bytes, "material 0: base colour");
    bytes = good;
    put_float(bytes, material_offset(0) + 28, 2.0f);
    refused(bytes, "material 0: roughness 2");
    // Triangle 2: a position, a normal, the material index.
    bytes = good;
    put_float(bytes, triangle_offset(2, 2) + 4, std::numeric_limits<float>::infinity());
    refused(bytes, "triangle 2: position");
    bytes = good;
    put_float(bytes, triangle_offset(2, 2) + 36, 3.0f);
    refused(bytes, "triangle 2: normal");
    bytes = good;
    bytes[triangle_offset(2, 2) + 72] = 7;
    refused(bytes, "triangle 2: material 7 is out of range (2 materials)");
    // Counts: negative, over the limit; truncation and trailing bytes.
    bytes = good;
    bytes[3] = 0x80;
    refused(bytes, "material count");
    bytes = good;
    const uint32_t too_many = kMaxGeometryTriangles + 1;
    std::memcpy(&bytes[material_offset(2)], &too_many, 4);
    refused(bytes, "exceeds the limit of " + std::to_string(kMaxGeometryTriangles));
    bytes = good;
    bytes.pop_back();
    refused(bytes, "ended after 2 of 3 triangles");
    bytes = good;
    bytes.push_back(0);
    refused(bytes, "ended before the count of its masks");
}

}  // namespace
}  // namespace lc
