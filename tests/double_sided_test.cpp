// glTF doubleSided in the G-buffer, rasterised and cast as rays alike: a
// single-sided surface seen from behind (its clockwise side) is culled, so the
// view passes to what lies beyond; a double-sided one is drawn from both sides
// and its back face is shaded with the normal reversed. A surface without
// vertex normals takes its face normal, turned to the camera.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "editor_client/render/renderer.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "render_test_support.h"

namespace lc {
namespace {

using client::PrimaryChoice;
using DoubleSided = test::VulkanTest;

constexpr uint32_t kSize = 16;

// A unit quad in the plane z = z, counter-clockwise seen from +z, with vertex
// normals along `normal` (none when zero), material `material`.
Mesh quad_at(float z, glm::vec3 normal, int material) {
    Mesh mesh;
    mesh.positions = {{-1.0f, -1.0f, z}, {1.0f, -1.0f, z}, {1.0f, 1.0f, z}, {-1.0f, 1.0f, z}};
    if (glm::dot(normal, normal) > 0.0f) mesh.normals.assign(4, normal);
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.material = material;
    return mesh;
}

Material grey(float value, bool double_sided) {
    Material m;
    m.base_color_factor = glm::vec4(value, value, value, 1.0f);
    m.metallic = 0.0f;
    m.double_sided = double_sided;
    return m;
}

// The scene's G-buffer from a camera on the z axis at `eye_z`, looking at the origin.
client::GBufferReadback gbuffer_of(vk::Context& context, Scene scene, PrimaryChoice primary, float eye_z) {
    client::update_scene_bounds(scene);  // the raster pass's depth range
    client::RenderSettings settings;
    settings.width = settings.height = kSize;
    settings.camera.eye = {0.0f, 0.0f, eye_z};
    settings.camera.target = {0.0f, 0.0f, 0.0f};
    settings.camera.yfov = 0.6f;
    return test::gbuffer_of(context, scene, primary, settings);
}

// The centre pixel: did it see geometry, its normal's z and its albedo.
struct CentreSample {
    bool geometry = false;
    float normal_z = 0.0f;
    float albedo = 0.0f;
};

CentreSample centre(const client::GBufferReadback& g) {
    const size_t i = 4 * (size_t(kSize / 2) * kSize + kSize / 2);
    if (g.position.size() <= i + 3) return {};
    return {g.position[i + 3] != 0.0f, g.normal[i + 2], g.albedo[i]};
}

class BothPrimaries : public DoubleSided, public ::testing::WithParamInterface<PrimaryChoice> {};

TEST_P(BothPrimaries, ASingleSidedBackFaceIsCulledAndTheViewPassesThrough) {
    Scene scene;
    scene.materials = {grey(0.2f, false), grey(0.8f, true)};
    scene.meshes = {quad_at(0.0f, {0, 0, 1}, 0),    // single-sided, facing +z
                    quad_at(-1.0f, {0, 0, 1}, 1)};  // double-sided, behind it seen from +z
    // From +z: the single-sided quad's front.
    const CentreSample front = centre(gbuffer_of(*context_, scene, GetParam(), 4.0f));
    ASSERT_TRUE(front.geometry);
    EXPECT_NEAR(front.albedo, 0.2f, 1e-5f);
    EXPECT_NEAR(front.normal_z, 1.0f, 1e-5f);
    // From -z: the double-sided quad's back (its normal reversed, towards -z);
    // the single-sided quad behind it would be seen from its back and is culled.
    scene.meshes = {quad_at(0.0f, {0, 0, 1}, 0), quad_at(1.0f, {0, 0, 1}, 1)};
    const CentreSample back = centre(gbuffer_of(*context_, scene, GetParam(), -4.0f));
    ASSERT_TRUE(back.geometry);
    EXPECT_NEAR(back.albedo, 0.8f, 1e-5f);
    EXPECT_NEAR(back.normal_z, -1.0f, 1e-5f);
    // The single-sided quad alone from behind: nothing.
    scene.meshes = {quad_at(0.0f, {0, 0, 1}, 0)};
    EXPECT_FALSE(centre(gbuffer_of(*context_, scene, GetParam(), -4.0f)).geometry);
}

TEST_P(BothPrimaries, TheBackFaceIsShadedByItsWindingNotByTheNormalsDirection) {
    // Vertex normals tilted away from the camera on the front face: glTF
    // keeps them (no flip); the same quad seen from behind, double-sided,
    // has them reversed.
    Scene scene;
    scene.materials = {grey(0.5f, true)};
    const glm::vec3 tilted = glm::normalize(glm::vec3(1.0f, 0.0f, -0.2f));
    scene.meshes = {quad_at(0.0f, tilted, 0)};
    const CentreSample front = centre(gbuffer_of(*context_, scene, GetParam(), 4.0f));
    ASSERT_TRUE(front.geometry);
    EXPECT_NEAR(front.normal_z, tilted.z, 1e-4f);
    const CentreSample back = centre(gbuffer_of(*context_, scene, GetParam(), -4.0f));
    ASSERT_TRUE(back.geometry);
    EXPECT_NEAR(back.normal_z, -tilted.z, 1e-4f);
}

TEST_P(BothPrimaries, WithoutVertexNormalsTheFaceNormalTurnsToTheCamera) {
    Scene scene;
    scene.materials = {grey(0.5f, true), grey(0.5f, false)};
    scene.meshes = {quad_at(0.0f, {0, 0, 0}, 0)};
    EXPECT_NEAR(centre(gbuffer_of(*context_, scene, GetParam(), 4.0f)).normal_z, 1.0f, 1e-4f);
    EXPECT_NEAR(centre(gbuffer_of(*context_, scene, GetParam(), -4.0f)).normal_z, -1.0f, 1e-4f);
    // Single-sided, no normals: still culled by winding from behind.
    scene.meshes = {quad_at(0.0f, {0, 0, 0}, 1)};
    EXPECT_TRUE(centre(gbuffer_of(*context_, scene, GetParam(), 4.0f)).geometry);
    EXPECT_FALSE(centre(gbuffer_of(*context_, scene, GetParam(), -4.0f)).geometry);
}

INSTANTIATE_TEST_SUITE_P(Primary, BothPrimaries, ::testing::Values(PrimaryChoice::kRaster, PrimaryChoice::kRays),
                         [](const ::testing::TestParamInfo<PrimaryChoice>& info) {
                             return info.param == PrimaryChoice::kRays ? std::string("Rays")
                                                                       : std::string("Raster");
                         });

}  // namespace
}  // namespace lc
