#pragma once
// Helpers for the renderer's and the editor's tests: a Vulkan context (or a
// clear skip when the machine has no Vulkan device), small scenes built in
// code and screenshot checks (hand-made trees: tree_fixtures.h).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "editor_client/render/gbuffer_surface.h"
#include "editor_client/render/output/image_io.h"
#include "editor_client/render/renderer.h"
#include "editor_client/scene/scene_generator.h"
#include "editor_client/vk/context.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/tree/gpu_layout.h"
#include "lightcuts/tree/light_tree.h"
#include "lightcuts/material_model.h"
#include "lightcuts/scene.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/dump.h"
#include "tree_fixtures.h"

namespace lc::test {

// The renderer over `scene` and `tree` (the import form; null: none), which
// it takes in its walk form (make_walk_tree), as the commands give it.
inline Result<std::unique_ptr<client::Renderer>> create_renderer(
    const vk::Context& context, const Scene& scene, const LightTree* tree,
    const client::RendererOptions& options = {}) {
    if (tree == nullptr) return client::Renderer::create(context, scene, nullptr, options);
    Result<WalkTree> walk = make_walk_tree(*tree);
    if (!walk) return make_error("light tree: " + walk.error());
    return client::Renderer::create(context, scene, &*walk, options);
}
// The renderer keeps the scene: a temporary is refused, as Renderer::create does.
Result<std::unique_ptr<client::Renderer>> create_renderer(
    const vk::Context& context, const Scene&& scene, const LightTree* tree,
    const client::RendererOptions& options = {}) = delete;

// Renderer::set_tree with the import form.
inline Status set_tree(client::Renderer& renderer, const LightTree* tree) {
    if (tree == nullptr) return renderer.set_tree(nullptr);
    Result<WalkTree> walk = make_walk_tree(*tree);
    if (!walk) return make_error("light tree: " + walk.error());
    return renderer.set_tree(&*walk);
}

// The scene's G-buffer as `settings` frames it, rasterised or cast as rays
// (`primary`); empty (with a test failure) when the renderer refuses.
inline client::GBufferReadback gbuffer_of(vk::Context& context, const Scene& scene,
                                          client::PrimaryChoice primary, const client::RenderSettings& settings) {
    client::RendererOptions options;
    options.primary = primary;
    Result<std::unique_ptr<client::Renderer>> renderer = create_renderer(context, scene, nullptr, options);
    EXPECT_TRUE(renderer.ok()) << renderer.error();
    if (!renderer.ok()) return {};
    Status drawn = (*renderer)->render_gbuffer(settings);
    EXPECT_TRUE(drawn.ok()) << drawn.error();
    Result<client::GBufferReadback> g = (*renderer)->read_gbuffer();
    EXPECT_TRUE(g.ok());
    return g.ok() ? std::move(g).value() : client::GBufferReadback{};
}

// The surface point the lighting pass saw at pixel i of a G-buffer read-back.
inline lc::SurfacePoint gbuffer_point(const client::GBufferReadback& g, size_t i) {
    return client::gbuffer_surface_point(g, i);
}

// A view of the furnished room (scene_generator.h) over the table towards the
// cabinet and pillars: edges, shadows and glossy highlights in one frame.
inline client::RenderCamera furnished_room_camera() {
    client::RenderCamera camera;
    camera.eye = {0.0f, 2.2f, 4.6f};
    camera.target = {0.0f, 0.4f, -1.0f};
    camera.yfov = 1.1f;
    return camera;
}

// `count` lights generated in the room's light box (scene_generator.h).
inline std::vector<SceneLight> room_lights(uint32_t count, uint64_t seed,
                                           client::LightTypeChoice type, float intensity) {
    client::LightLayoutOptions options;
    options.count = count;
    options.seed = seed;
    options.type = type;
    options.box_min = client::kRoomLightBoxMin;
    options.box_max = client::kRoomLightBoxMax;
    options.intensity = intensity;
    Result<std::vector<SceneLight>> lights = client::generate_lights(options);
    EXPECT_TRUE(lights.ok()) << lights.error();
    return lights.ok() ? *lights : std::vector<SceneLight>{};
}

// The generated room with 12 point lights of range 5 from `seed`.
inline Scene lit_room(uint64_t seed) {
    Scene scene = client::make_room_scene();
    client::LightLayoutOptions layout;
    layout.count = 12;
    layout.seed = seed;
    layout.box_min = client::kRoomLightBoxMin;
    layout.box_max = client::kRoomLightBoxMax;
    layout.range = 5.0f;
    Result<std::vector<SceneLight>> lights = client::generate_lights(layout);
    EXPECT_TRUE(lights.ok()) << lights.error();
    if (lights.ok()) scene.lights = *lights;
    return scene;
}

// lit_room with its lights 1000x brighter: at exposure 1 the image is white,
// so an automatic exposure must be far below 1.
inline Scene overexposed_lit_room(uint64_t seed) {
    Scene scene = lit_room(seed);
    for (SceneLight& light : scene.lights) light.intensity *= 1000.0f;
    return scene;
}

// A screenshot shows something: more than `min_colours` colours (shaded
// images have many, the cuts view one per distinct cut) and at least a
// quarter of its pixels lit.
inline void expect_not_blank(const client::Rgba8Image& image, const std::string& what,
                             size_t min_colours = 16) {
    std::set<uint32_t> colours;
    size_t lit = 0;
    for (size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
        colours.insert(image.rgba[i] | image.rgba[i + 1] << 8 | image.rgba[i + 2] << 16);
        lit += (image.rgba[i] + image.rgba[i + 1] + image.rgba[i + 2]) > 30 ? 1 : 0;
    }
    EXPECT_GT(colours.size(), min_colours) << what << " is blank";
    EXPECT_GT(lit, image.rgba.size() / 4 / 4) << what << " is mostly black";
}

// The paper's agglomerative tree over `lights` (empty, and a failure, if the build fails).
inline LightTree agglomerative_tree(const std::vector<SceneLight>& lights) {
    bake::BuildOptions options;
    options.builder = BuilderKind::kAgglomerative;
    Result<bake::BuildResult> built = bake::build_light_tree(lights, options, nullptr);
    EXPECT_TRUE(built.ok()) << built.error();
    return built.ok() ? std::move(built->tree) : LightTree{};
}

// The scene's lights baked in process and written as a result channel dump
// (what `bake -o` writes) to dir/room.lcut, for `--tree`.
inline std::filesystem::path write_tree_dump(const Scene& scene, const std::filesystem::path& dir) {
    Result<bake::BuildResult> built = bake::build_light_tree(scene.lights, {}, nullptr);
    EXPECT_TRUE(built.ok()) << built.error();
    const std::filesystem::path path = dir / "room.lcut";
    if (built.ok()) {
        Status written = write_dump(
            path, ChannelDump{lightcuts_result_channel_name(), encode_result_channel(built->tree)});
        EXPECT_TRUE(written.ok()) << written.error();
    }
    return path;
}

// Null (and the reason in `why`) when no usable Vulkan device exists.
inline std::unique_ptr<vk::Context> make_headless_context(std::string& why) {
    // Tests always validate (ctest sets LC_VALIDATION=1 too).
    vk::ContextOptions options;
    options.validation = true;
    Result<vk::Context> context = vk::Context::create(options);
    if (!context) {
        why = context.error();
        return nullptr;
    }
    return std::make_unique<vk::Context>(std::move(context).value());
}

#define LC_REQUIRE_VULKAN(context)                                            \
    do {                                                                      \
        std::string lc_vulkan_why_;                                           \
        context = ::lc::test::make_headless_context(lc_vulkan_why_);          \
        if (!context) GTEST_SKIP() << "no Vulkan device: " << lc_vulkan_why_; \
    } while (0)

// A fixture for tests that render: a validating headless context (or the
// test skips), which must have reported no validation message at the end.
class VulkanTest : public ::testing::Test {
protected:
    void SetUp() override { LC_REQUIRE_VULKAN(context_); }
    void TearDown() override {
        if (context_) {
            EXPECT_EQ(context_->validation_message_count(), 0u);
        }
    }
    std::unique_ptr<vk::Context> context_;
};

// A PNG the test wrote (empty, and a failure, when it cannot be read).
inline client::Rgba8Image read_image(const std::filesystem::path& path) {
    Result<client::Rgba8Image> image = client::read_png(path);
    EXPECT_TRUE(image.ok()) << path << ": " << (image.ok() ? "" : image.error());
    return image.ok() ? std::move(image).value() : client::Rgba8Image{};
}

// White, rough, dielectric: Lambert with albedo 1, so radiance is E / pi.
inline lc::Material white_lambert() {
    lc::Material m;
    m.base_color_factor = glm::vec4(1.0f);
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    return m;
}

inline lc::Mesh make_quad(const glm::vec3& corner, const glm::vec3& edge_u,
                              const glm::vec3& edge_v, int material) {
    lc::Mesh mesh;
    glm::vec3 normal = glm::normalize(glm::cross(edge_u, edge_v));
    mesh.positions = {corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v};
    mesh.normals = {normal, normal, normal, normal};
    mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.material = material;
    return mesh;
}

inline SceneLight point_light(glm::vec3 position, glm::vec3 color, float intensity,
                              float range = 0.0f) {
    SceneLight light;
    light.type = LightType::kPoint;
    light.position = position;
    light.color = color;
    light.intensity = intensity;
    light.range = range;
    return light;
}

inline SceneLight spot_light(glm::vec3 position, glm::vec3 direction, glm::vec3 color,
                             float intensity, float inner, float outer, float range = 0.0f) {
    SceneLight light = point_light(position, color, intensity, range);
    light.type = LightType::kSpot;
    light.direction = glm::normalize(direction);
    light.inner_cone_angle = inner;
    light.outer_cone_angle = outer;
    return light;
}

// A cosine emitter facing `normal` (an area-light sample).
inline SceneLight oriented_light(glm::vec3 position, glm::vec3 normal, glm::vec3 color,
                                 float intensity) {
    SceneLight light = point_light(position, color, intensity);
    light.type = LightType::kOriented;
    light.direction = glm::normalize(normal);
    return light;
}

inline SceneLight directional_light(glm::vec3 direction, glm::vec3 color, float lux) {
    SceneLight light;
    light.type = LightType::kDirectional;
    light.direction = glm::normalize(direction);
    light.color = color;
    light.intensity = lux;
    return light;
}

// A 10 x 10 floor at y = 0 and a back wall at z = -5 with two materials; no lights.
inline lc::Scene make_floor_scene() {
    lc::Scene scene;
    lc::Material floor;
    floor.base_color_factor = {0.8f, 0.7f, 0.6f, 1.0f};
    floor.metallic = 0.0f;
    lc::Material wall;
    wall.base_color_factor = {0.3f, 0.5f, 0.9f, 1.0f};
    wall.metallic = 0.0f;
    scene.materials = {floor, wall};
    scene.meshes.push_back(make_quad({-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, 0));
    scene.meshes.push_back(make_quad({-5, 0, -5}, {10, 0, 0}, {0, 5, 0}, 1));
    scene.bounds_min = {-5, 0, -5};
    scene.bounds_max = {5, 5, 5};
    return scene;
}

inline client::RenderCamera floor_camera() {
    client::RenderCamera camera;
    camera.eye = {0.0f, 6.0f, 9.0f};
    camera.target = {0.0f, 0.5f, -1.0f};
    camera.yfov = 0.9f;
    return camera;
}

inline void set_unit_guid(SceneLight& light, uint32_t index) {
    light.guid = Guid{1, 2, 3, index + 1};
}

}  // namespace lc::test
