// Alpha masks on the server: the geometry channel carries them (keep bits and
// the masked triangles' texture coordinates) only when a scene has them, the
// reader refuses bad mask records naming them, and the server's Embree ray
// caster lets rays through the texels a mask cuts out, for occlusion and for
// the nearest hit alike. The client sends its MASK materials' masks and a
// see-through mask for surfaces that cast no shadow.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/surface_geometry.h"
#include "indirect_scenes.h"
#include "lightmass_server/raycast/ray_caster.h"
#include "protocol/geometry_channel.h"
#include "test_paths.h"

namespace lc {
namespace {

constexpr uint32_t kChecks = 8;  // the checkerboard's squares per side

// An n x n checkerboard that keeps texel (x, y) where x + y is even.
SurfaceMask checkerboard(uint32_t n) {
    AlphaMask alpha;
    alpha.width = alpha.height = int(n);
    alpha.keep_threshold = 128;
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) alpha.alpha.push_back((x + y) % 2 == 0 ? 255 : 0);
    return surface_mask_of(alpha);
}

// The unit square [0, 1]^2 in x and z at height y, two triangles, with
// texture coordinates (x, z) when masked by `mask` (-1: opaque).
void add_square(SceneGeometry& g, float y, int mask) {
    const glm::vec3 p[4] = {{0, y, 0}, {1, y, 0}, {1, y, 1}, {0, y, 1}};
    const uint32_t corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& c : corners) {
        if (mask >= 0) {
            MaskedTriangle t;
            t.triangle = uint32_t(g.triangles.size());
            t.mask = uint32_t(mask);
            for (int k = 0; k < 3; ++k) t.uvs[k] = glm::vec2(p[c[k]].x, p[c[k]].z);
            g.masked_triangles.push_back(t);
        }
        g.triangles.push_back(test::flat_triangle(p[c[0]], p[c[1]], p[c[2]], 0));
    }
}

// A masked fence at y = 1 under an opaque ceiling at y = 2.
SceneGeometry fence_under_ceiling() {
    SceneGeometry g;
    g.materials.push_back({});
    g.masks.push_back(checkerboard(kChecks));
    add_square(g, 1.0f, 0);
    add_square(g, 2.0f, -1);
    return g;
}

bool checker_keeps(float x, float z) {
    return (int(x * kChecks) + int(z * kChecks)) % 2 == 0;
}

TEST(GeometryMasks, TheChannelCarriesMasksOnlyWhenThereAreSome) {
    SceneGeometry g = fence_under_ceiling();
    const std::vector<uint8_t> bytes = encode_geometry_channel(g);
    EXPECT_EQ(bytes.size(), geometry_channel_bytes(1, 4) + 3 * 4 + geometry_mask_record_bytes() + 2 * 4 +
                                2 * geometry_masked_triangle_record_bytes());
    // Byte by byte and whole: the same masks back.
    for (size_t chunk : {size_t(1), size_t(7), bytes.size()}) {
        GeometryChannelReader reader;
        for (size_t at = 0; at < bytes.size(); at += chunk) {
            const size_t n = std::min(chunk, bytes.size() - at);
            ASSERT_TRUE(reader.consume(std::span(bytes).subspan(at, n)).ok());
        }
        Result<SceneGeometry> decoded = reader.finish();
        ASSERT_TRUE(decoded.ok()) << decoded.error();
        EXPECT_EQ(decoded->masks, g.masks);
        EXPECT_EQ(decoded->masked_triangles, g.masked_triangles);
    }
    // Without masks: the channel as it always was.
    g.masks.clear();
    g.masked_triangles.clear();
    EXPECT_EQ(encode_geometry_channel(g).size(), geometry_channel_bytes(1, 4));
}

TEST(GeometryMasks, ADegenerateTriangleBeforeAMaskedOneShiftsItsIndex) {
    SceneGeometry g;
    g.materials.push_back({});
    g.masks.push_back(checkerboard(2));
    SurfaceTriangle degenerate;  // collinear corners, per-face (zero) normals
    degenerate.positions[1] = {1, 0, 0};
    degenerate.positions[2] = {2, 0, 0};
    g.triangles.push_back(degenerate);
    add_square(g, 1.0f, 0);
    // The degenerate one masked too: its mask is dropped with it.
    g.masked_triangles.insert(g.masked_triangles.begin(), MaskedTriangle{0, 0, {}});
    size_t skipped = 0;
    Result<SceneGeometry> decoded = decode_geometry_channel(encode_geometry_channel(g), &skipped);
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_EQ(skipped, 1u);
    ASSERT_EQ(decoded->masked_triangles.size(), 2u);
    EXPECT_EQ(decoded->masked_triangles[0].triangle, 0u);
    EXPECT_EQ(decoded->masked_triangles[1].triangle, 1u);
    EXPECT_EQ(decoded->masked_triangles[1].uvs[1], g.masked_triangles[2].uvs[1]);
}

TEST(GeometryMasks, BadMaskRecordsAreRefusedNamingThem) {
    const SceneGeometry good = fence_under_ceiling();
    auto refused = [](const SceneGeometry& g, const std::string& expected) {
        Result<SceneGeometry> decoded = decode_geometry_channel(encode_geometry_channel(g));
        ASSERT_FALSE(decoded.ok()) << "expected: " << expected;
        EXPECT_NE(decoded.error().find(expected), std::string::npos) << decoded.error();
    };
    SceneGeometry g = good;
    g.masked_triangles[1].mask = 3;
    refused(g, "masked triangle 1: mask 3 is out of range (1 masks)");
    g = good;
    std::swap(g.masked_triangles[0], g.masked_triangles[1]);
    refused(g, "masked triangle 1: triangle 0 is out of order");
    g = good;
    g.masked_triangles[1].triangle = 9;
    refused(g, "triangle 9 is out of order or range (4 triangles)");
    g = good;
    g.masked_triangles[0].uvs[2].y = std::numeric_limits<float>::infinity();
    refused(g, "masked triangle 0: texture coordinate inf is not finite");
    g = good;
    g.masks[0].keep_bits.push_back(0);  // a word more than 8 x 8 texels need
    refused(g, "mask word count 3 is not the masks' 2 words");
    g = good;
    g.masks[0].width = 0;
    refused(g, "mask 0: 0 x 8 texels is not within 1 and 67108864");
    g = good;
    g.masks[0].width = g.masks[0].height = 1u << 14;
    refused(g, "16384 x 16384 texels is not within 1 and 67108864");
    // Cut short inside the masked triangles.
    std::vector<uint8_t> bytes = encode_geometry_channel(good);
    bytes.resize(bytes.size() - 5);
    Result<SceneGeometry> short_channel = decode_geometry_channel(bytes);
    ASSERT_FALSE(short_channel.ok());
    EXPECT_NE(short_channel.error().find("ended after 1 of 2 masked triangles"), std::string::npos)
        << short_channel.error();
}

TEST(GeometryMasks, RaysPassWhereTheMaskCutsTheSurfaceOut) {
    auto caster = RayCaster::build(fence_under_ceiling(), 1);
    ASSERT_TRUE(caster.ok()) << caster.error();
    EXPECT_EQ(caster->masked_triangle_count(), 2u);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const int rays = 20000;
    int blocked = 0, agree = 0;
    for (int i = 0; i < rays; ++i) {
        const float x = unit(rng), z = unit(rng);
        const bool kept = checker_keeps(x, z);
        const bool occluded = caster->occluded({x, 0.0f, z}, {0, 1, 0}, 0.0f, 1.5f);
        blocked += occluded ? 1 : 0;
        // The nearest hit: the fence where kept, else the opaque ceiling above.
        const auto hit = caster->intersect({x, 0.0f, z}, {0, 1, 0}, 0.0f, 10.0f);
        const bool right_hit = hit && (kept ? hit->triangle < 2 && std::abs(hit->distance - 1.0f) < 1e-5f
                                            : hit->triangle >= 2 && std::abs(hit->distance - 2.0f) < 1e-5f);
        agree += occluded == kept && right_hit ? 1 : 0;
    }
    std::printf("  server: %d of %d rays blocked by the checkerboard (analytic 0.5), %d agree texel by texel\n",
                blocked, rays, agree);
    // Half the checkerboard is kept: the shadowed fraction within 1% of it.
    EXPECT_NEAR(double(blocked) / rays, 0.5, 0.01);
    EXPECT_EQ(agree, rays);
}

TEST(GeometryMasks, TheClientSendsMasksAndSeeThroughSurfaces) {
    LC_REQUIRE_SHARED_SCENES();
    const std::filesystem::path file = test::shared_scenes_dir() / "AlphaBlendModeTest" / "AlphaBlendModeTest.gltf";
    Result<Scene> scene = client::load_scene(file);
    ASSERT_TRUE(scene.ok()) << scene.error();
    const SceneGeometry g = client::extract_surface_geometry(*scene);
    std::vector<AlphaMask> alpha;
    const std::vector<int32_t> mesh_mask = mesh_alpha_masks(*scene, alpha);
    size_t masked_meshes = 0, see_through_meshes = 0, expected = 0;
    for (size_t i = 0; i < scene->meshes.size(); ++i) {
        const Mesh& mesh = scene->meshes[i];
        const bool see_through = !casts_shadows(*scene, mesh);
        see_through_meshes += see_through ? 1 : 0;
        masked_meshes += !see_through && mesh_mask[i] >= 0 ? 1 : 0;
        if (see_through || mesh_mask[i] >= 0) expected += mesh.indices.size() / 3;
    }
    ASSERT_GT(masked_meshes, 0u);
    ASSERT_GT(see_through_meshes, 0u);
    // Every cut-out and every see-through triangle is masked, nothing else.
    EXPECT_EQ(g.masked_triangles.size(), expected);
    const SurfaceMask see_through{1, 1, {0u}};
    EXPECT_NE(std::find(g.masks.begin(), g.masks.end(), see_through), g.masks.end());
    // And the channel carries them to the server intact.
    Result<SceneGeometry> decoded = decode_geometry_channel(encode_geometry_channel(g));
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_EQ(decoded->masks, g.masks);
}

}  // namespace
}  // namespace lc
