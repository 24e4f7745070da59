#pragma once
// Helpers for the renderer's tests: a Vulkan context (or a clear skip when the
// machine has no Vulkan device), small scenes built in code, and a hand-made
// light tree.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "lightcuts/cpu_evaluator.h"
#include "lightcuts/material_model.h"
#include "editor_client/render/renderer.h"
#include "lightcuts/scene.h"
#include "editor_client/scene/scene_generator.h"
#include "lightmass_server/tree_builder.h"
#include "editor_client/vk/context.h"
#include "lightcuts/light_tree.h"

namespace lc::test {

// The surface point the lighting pass saw at pixel i of a G-buffer read-back.
inline lc::SurfacePoint gbuffer_point(const client::GBufferReadback& g, size_t i) {
    lc::SurfacePoint p;
    p.position = {g.position[4 * i], g.position[4 * i + 1], g.position[4 * i + 2]};
    p.normal = {g.normal[4 * i], g.normal[4 * i + 1], g.normal[4 * i + 2]};
    const glm::dvec3 base(g.albedo[4 * i], g.albedo[4 * i + 1], g.albedo[4 * i + 2]);
    const shading::SurfaceMaterial m =
        shading::surface_material(base, g.albedo[4 * i + 3], g.normal[4 * i + 3]);
    p.albedo = m.diffuse;
    p.specular = m.specular;
    p.exponent = m.exponent;
    p.mirror = shading::mirror_direction(p.normal, p.position, glm::dvec3(g.eye));
    return p;
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

// The paper's agglomerative tree over `lights` (empty, and a failure, if the build fails).
inline LightTree agglomerative_tree(const std::vector<SceneLight>& lights) {
    bake::BuildOptions options;
    options.builder = BuilderKind::kAgglomerative;
    Result<bake::BuildResult> built = bake::build_light_tree(lights, options, nullptr);
    EXPECT_TRUE(built.ok()) << built.error();
    return built.ok() ? std::move(built->tree) : LightTree{};
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

// Builds a tree over `lights` by hand: pairs neighbours level by level in index
// order (an odd node is carried up), the representative is the left child's,
// intensity sums, and the influence radius encloses the children's spheres
// (unbounded when a child is). Lights of different types are joined only by
// a mixed_types junction at the top.
inline LightTree make_pairing_tree(const std::vector<SceneLight>& lights) {
    struct Building {
        LightTreeNode node;
        int left = -1, right = -1;  // indices into `all`
    };
    std::vector<Building> all;
    auto leaf = [](const SceneLight& l) {
        LightTreeNode n;
        n.guid = l.guid;
        n.type = l.type;
        n.position = l.position;
        n.direction = l.direction;
        n.range = l.range;
        n.spot_cos_inner = std::cos(l.inner_cone_angle);
        n.spot_cos_outer = std::cos(l.outer_cone_angle);
        n.intensity = l.color * l.intensity;
        n.brightness = l.intensity;
        n.radius = l.range > 0.0f ? l.range : kUnboundedRadius;
        n.bbox_min = n.bbox_max = l.position;
        return n;
    };
    auto join = [&](int a, int b) {
        Building parent;
        const LightTreeNode& l = all[a].node;
        const LightTreeNode& r = all[b].node;
        parent.node = l;  // representative parameters: the left child's
        parent.node.intensity = l.intensity + r.intensity;
        parent.node.brightness = l.brightness + r.brightness;
        parent.node.mixed_types = l.mixed_types || r.mixed_types || l.type != r.type;
        if (l.radius < 0.0f || r.radius < 0.0f) {
            parent.node.radius = kUnboundedRadius;
        } else {
            float reach = glm::length(r.position - l.position) + r.radius;
            parent.node.radius = std::max(l.radius, reach);
        }
        parent.node.bbox_min = glm::min(l.bbox_min, r.bbox_min);
        parent.node.bbox_max = glm::max(l.bbox_max, r.bbox_max);
        parent.left = a;
        parent.right = b;
        all.push_back(parent);
        return int(all.size()) - 1;
    };
    std::vector<int> level;
    for (const SceneLight& l : lights) {
        all.push_back({leaf(l)});
        level.push_back(int(all.size()) - 1);
    }
    while (level.size() > 1) {
        std::vector<int> next;
        for (size_t i = 0; i + 1 < level.size(); i += 2)
            next.push_back(join(level[i], level[i + 1]));
        if (level.size() % 2 == 1) next.push_back(level.back());
        level = next;
    }
    // Breadth-first renumbering from the root (iterative).
    LightTree tree;
    if (level.empty()) return tree;
    std::vector<int> order{level[0]};
    for (size_t i = 0; i < order.size(); ++i) {
        if (all[order[i]].left >= 0) {
            order.push_back(all[order[i]].left);
            order.push_back(all[order[i]].right);
        }
    }
    std::vector<int> new_index(all.size(), -1);
    for (size_t i = 0; i < order.size(); ++i) new_index[order[i]] = int(i);
    for (int old : order) {
        LightTreeNode n = all[old].node;
        n.left = all[old].left >= 0 ? new_index[all[old].left] : kNoChild;
        n.right = all[old].right >= 0 ? new_index[all[old].right] : kNoChild;
        tree.nodes.push_back(n);
    }
    // Representatives: follow left children down to a leaf (iteratively).
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        int32_t r = int32_t(i);
        while (tree.nodes[r].left != kNoChild) r = tree.nodes[r].left;
        tree.nodes[i].representative = r;
        if (tree.nodes[i].is_leaf()) ++tree.leaf_count;
    }
    return tree;
}

}  // namespace lc::test
