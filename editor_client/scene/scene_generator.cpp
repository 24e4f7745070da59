#include "editor_client/scene/scene_generator.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/inputs/scene_guid.h"
#include "editor_client/scene/surface_sampler.h"
#include "lightcuts/seeded_mixer.h"
#include "protocol/channel_records.h"

namespace lc::client {
namespace {

// XORed into every layout seed (the bytes spell "lightcu"); part of the
// layouts' bytes: changing it changes every generated scene.
constexpr uint64_t kLayoutSeedSalt = 0x6c696768746375ull;

void append_u64(std::vector<uint8_t>& bytes, uint64_t v) {
    for (int i = 0; i < 8; ++i) bytes.push_back(uint8_t(v >> (8 * i)));
}

Guid generated_light_guid(const Guid& salt, uint64_t seed, uint32_t index) {
    const std::string tag = "lc.generated-light";
    std::vector<uint8_t> bytes(tag.begin(), tag.end());
    append_u64(bytes, (uint64_t(salt.a) << 32) | salt.b);
    append_u64(bytes, (uint64_t(salt.c) << 32) | salt.d);
    append_u64(bytes, seed);
    append_u64(bytes, index);
    return Guid::from_bytes(bytes);
}

Guid named_guid(std::string_view text) {
    std::vector<uint8_t> bytes(text.begin(), text.end());
    return Guid::from_bytes(bytes);
}

// A direction within `max_angle` of straight down (-Y), uniform over the cap.
glm::vec3 direction_near_down(SplitMix64& rng, double max_angle) {
    const double cos_max = std::cos(max_angle);
    const double cos_theta = 1.0 - rng.uniform() * (1.0 - cos_max);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double phi = 2.0 * std::numbers::pi * rng.uniform();
    return glm::normalize(glm::vec3(float(sin_theta * std::cos(phi)), float(-cos_theta),
                                    float(sin_theta * std::sin(phi))));
}

LightType type_for(LightTypeChoice choice, uint32_t index) {
    switch (choice) {
        case LightTypeChoice::kPoint:
            return LightType::kPoint;
        case LightTypeChoice::kSpot:
            return LightType::kSpot;
        case LightTypeChoice::kDirectional:
            return LightType::kDirectional;
        case LightTypeChoice::kMixed:
            break;
    }
    constexpr std::array<LightType, 3> cycle{LightType::kPoint, LightType::kSpot,
                                             LightType::kDirectional};
    return cycle[index % 3];
}

// Cells per axis of the most cubic grid with at least `count` cells: start
// from the proportional estimate, then split the axis with the largest cells.
std::array<uint32_t, 3> grid_dimensions(const glm::dvec3& extent, uint32_t count) {
    std::array<uint32_t, 3> n{1, 1, 1};
    const double largest = std::max({extent.x, extent.y, extent.z});
    std::array<bool, 3> active{};
    int active_count = 0;
    double volume = 1.0;
    for (int a = 0; a < 3; ++a) {
        active[size_t(a)] = extent[a] > 1e-6 * std::max(1.0, largest);
        if (active[size_t(a)]) {
            ++active_count;
            volume *= extent[a];
        }
    }
    if (active_count == 0 || count <= 1) return n;
    const double cells_per_unit = std::pow(double(count) / volume, 1.0 / active_count);
    for (int a = 0; a < 3; ++a) {
        if (active[size_t(a)]) {
            n[size_t(a)] =
                uint32_t(std::clamp(std::floor(extent[a] * cells_per_unit), 1.0, double(count)));
        }
    }
    auto cells = [&] { return uint64_t(n[0]) * n[1] * n[2]; };
    while (cells() < count) {
        int best = -1;
        double best_size = -1.0;
        for (int a = 0; a < 3; ++a) {
            if (!active[size_t(a)]) continue;
            const double size = extent[a] / n[size_t(a)];
            if (size > best_size) {
                best_size = size;
                best = a;
            }
        }
        n[size_t(best)] += 1;
    }
    return n;
}

void add_quad(Scene& scene, const std::array<glm::vec3, 4>& corners, const glm::vec3& normal,
              int material) {
    Mesh mesh;
    mesh.positions.assign(corners.begin(), corners.end());
    mesh.normals.assign(4, normal);
    mesh.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    // Counter-clockwise seen from the side the normal points to (front faces).
    const glm::vec3 face = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
    if (glm::dot(face, normal) >= 0.0f) {
        mesh.indices = {0, 1, 2, 0, 2, 3};
    } else {
        mesh.indices = {0, 2, 1, 0, 3, 2};
    }
    mesh.material = material;
    scene.meshes.push_back(std::move(mesh));
}

// A horizontal floor quad at y = 0 facing up.
void add_floor(Scene& scene, float x0, float z0, float x1, float z1, int material) {
    add_quad(
        scene,
        {glm::vec3(x0, 0, z0), glm::vec3(x1, 0, z0), glm::vec3(x1, 0, z1), glm::vec3(x0, 0, z1)},
        glm::vec3(0, 1, 0), material);
}

Material diffuse(float grey) {
    Material m;
    m.base_color_factor = glm::vec4(grey, grey, grey, 1.0f);
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    return m;
}

// Thesis (x, y, z) with +Z up -> glTF (x, z, -y) with +Y up.
glm::vec3 from_thesis(float x, float y, float z) {
    return {x, z, -y};
}

// Unreal's FColor is sRGB-encoded 8-bit; our colours are linear.
float srgb_to_linear(int c8) {
    const double c = c8 / 255.0;
    return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

SceneLight point_light(const glm::vec3& position, float intensity, float range,
                       const glm::vec3& color, const Guid& guid) {
    SceneLight light;
    light.guid = guid;
    light.type = LightType::kPoint;
    light.position = position;
    light.color = color;
    light.intensity = intensity;
    light.range = range;
    return light;
}

Camera look_at(std::string name, glm::vec3 eye, glm::vec3 target, float yfov) {
    Camera camera;
    camera.name = std::move(name);
    camera.eye = eye;
    camera.target = target;
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    camera.yfov = yfov;
    return camera;
}

void finish(Scene& scene) {
    update_scene_bounds(scene);
    scene.guid = compute_scene_guid(scene);
}

}  // namespace

Result<LightLayout> parse_light_layout(std::string_view text) {
    if (text == "random") return LightLayout::kRandom;
    if (text == "grid") return LightLayout::kGrid;
    if (text == "surface") return LightLayout::kSurface;
    return make_error("unknown light layout '" + std::string(text) +
                      "' (expected random, grid or surface)");
}

Result<LightTypeChoice> parse_light_type_choice(std::string_view text) {
    if (text == "point") return LightTypeChoice::kPoint;
    if (text == "spot") return LightTypeChoice::kSpot;
    if (text == "directional") return LightTypeChoice::kDirectional;
    if (text == "mixed") return LightTypeChoice::kMixed;
    return make_error("unknown light type '" + std::string(text) +
                      "' (expected point, spot, directional or mixed)");
}

namespace {

Status check_layout_options(const LightLayoutOptions& options) {
    if (options.count == 0) return make_error("the light count must be at least 1");
    if (options.count > kMaxSceneLights) {
        return make_error("the light count " + std::to_string(options.count) +
                          " exceeds the limit of " + std::to_string(kMaxSceneLights));
    }
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(options.box_min[a]) || !std::isfinite(options.box_max[a])) {
            return make_error("the light box has a non-finite coordinate");
        }
        if (options.box_min[a] > options.box_max[a]) {
            return make_error("the light box is inverted on axis " + std::string(1, "xyz"[a]) +
                              " (min " + std::to_string(options.box_min[a]) + " > max " +
                              std::to_string(options.box_max[a]) + ")");
        }
    }
    if (options.intensity && (!std::isfinite(*options.intensity) || *options.intensity < 0.0f)) {
        return make_error("the intensity must be finite and >= 0");
    }
    if (!std::isfinite(options.range) || options.range < 0.0f) {
        return make_error("the range must be finite and >= 0 (0: unbounded)");
    }
    return Ok{};
}

std::string box_text(const glm::vec3& lo, const glm::vec3& hi) {
    char text[160];
    std::snprintf(text, sizeof(text), "(%g, %g, %g) - (%g, %g, %g)", lo.x, lo.y, lo.z, hi.x, hi.y,
                  hi.z);
    return text;
}

// Surface layout: see generate_lights in the header.
Result<std::vector<SceneLight>> generate_surface_lights(const LightLayoutOptions& options) {
    if (options.type == LightTypeChoice::kDirectional) {
        return make_error("the surface layout places lights on surfaces; directional lights have "
                          "no position there (use point, spot or mixed)");
    }
    if (options.surfaces == nullptr) {
        return make_error("the surface layout needs the scene's triangles, and no scene was given");
    }
    const glm::dvec3 lo(options.box_min);
    const glm::dvec3 hi(options.box_max);
    Result<SurfaceSelection> selected = select_surfaces(*options.surfaces, lo, hi);
    if (!selected) return make_error(selected.error());
    const SurfaceSelection& selection = selected.value();
    if (selection.usable_triangles == 0) {
        return make_error("the scene has no triangle with a non-zero area to place lights on");
    }
    if (selection.triangles.empty()) {
        return make_error("no surface of the scene lies inside the box " +
                          box_text(options.box_min, options.box_max) + " (no centroid of its " +
                          std::to_string(selection.usable_triangles) +
                          " triangles is in it); give a --box around some surfaces");
    }
    // A light exactly on its surface would light that surface at cos = 0 and
    // make the surface's own shading degenerate (0/0 direction at the light's
    // foot), so it stands a little in front of it.
    const double offset = kSurfaceLightOffset * selection.scene_diagonal;
    SplitMix64 rng(options.seed ^ kLayoutSeedSalt);

    std::vector<SceneLight> lights;
    lights.reserve(options.count);
    for (uint32_t i = 0; i < options.count; ++i) {
        Result<SurfacePoint> drawn = draw_kept_point(selection, rng);
        if (!drawn) return make_error(drawn.error());
        const SurfaceTriangle& tri = *drawn->triangle;
        const glm::dvec3 on_surface = drawn->position;
        // Far from the origin a float step may exceed the offset and round the
        // light onto or behind its surface: double the offset until it is in front.
        glm::vec3 position(0.0f);
        bool placed = false;
        for (int attempt = 0; attempt < 64 && !placed; ++attempt) {
            position = glm::vec3(on_surface + std::ldexp(offset, attempt) * tri.front);
            const double height = glm::dot(glm::dvec3(position) - tri.a, tri.front);
            placed = std::isfinite(height) && height >= 0.5 * offset;
        }
        if (!placed) {
            return make_error("cannot place a light in front of a surface in float precision "
                              "(is the scene finite?)");
        }

        SceneLight light;
        light.guid = generated_light_guid(options.guid_salt, options.seed, i);
        const bool spot = options.type == LightTypeChoice::kSpot ||
                          (options.type == LightTypeChoice::kMixed && i % 2 == 1);
        light.type = spot ? LightType::kSpot : LightType::kPoint;
        light.position = position;
        light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        light.range = options.range;
        light.classic = options.classic;
        light.intensity = options.intensity.value_or(kDefaultPointIntensity);
        if (spot) {
            // A hemispherical emitter: it lights only the side its surface faces.
            light.direction = glm::vec3(tri.front);
            light.inner_cone_angle = 0.0f;
            light.outer_cone_angle = kHemisphereSpotOuter;
        }
        lights.push_back(light);
    }
    return lights;
}

}  // namespace

Result<std::vector<SceneLight>> generate_lights(const LightLayoutOptions& options) {
    if (Status valid = check_layout_options(options); !valid) return make_error(valid.error());
    if (options.layout == LightLayout::kSurface) return generate_surface_lights(options);

    const glm::dvec3 lo(options.box_min);
    const glm::dvec3 extent = glm::dvec3(options.box_max) - lo;
    SplitMix64 rng(options.seed ^ kLayoutSeedSalt);
    const std::array<uint32_t, 3> dims = grid_dimensions(extent, options.count);

    std::vector<SceneLight> lights;
    lights.reserve(options.count);
    for (uint32_t i = 0; i < options.count; ++i) {
        SceneLight light;
        light.guid = generated_light_guid(options.guid_salt, options.seed, i);
        light.type = type_for(options.type, i);
        light.range = options.range;
        light.classic = options.classic;
        light.intensity = options.intensity.value_or(light.type == LightType::kDirectional
                                                         ? kDefaultDirectionalIntensity
                                                         : kDefaultPointIntensity);
        glm::dvec3 position;
        if (options.layout == LightLayout::kRandom) {
            position = lo + extent * glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform());
        } else {
            const uint32_t jx = i % dims[0];
            const uint32_t jz = (i / dims[0]) % dims[2];
            const uint32_t jy = i / (dims[0] * dims[2]);
            position = lo + extent * glm::dvec3((jx + 0.5) / dims[0], (jy + 0.5) / dims[1],
                                                (jz + 0.5) / dims[2]);
        }
        light.position = glm::vec3(position);
        light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        if (options.layout == LightLayout::kRandom) {
            // Drawn for every light (not only oriented ones) so a light's
            // position does not depend on the types before it.
            const glm::vec3 spot_dir = direction_near_down(rng, std::numbers::pi / 6.0);
            const glm::vec3 sun_dir = direction_near_down(rng, std::numbers::pi / 3.0);
            if (light.type == LightType::kSpot) light.direction = spot_dir;
            if (light.type == LightType::kDirectional) light.direction = sun_dir;
        }
        if (light.type == LightType::kSpot) {
            light.inner_cone_angle = kGeneratedSpotInner;
            light.outer_cone_angle = kGeneratedSpotOuter;
        }
        lights.push_back(light);
    }
    return lights;
}

Scene make_room_scene() {
    Scene scene;
    scene.materials.push_back(diffuse(0.7f));
    const glm::vec3 a = kRoomMin;
    const glm::vec3 b = kRoomMax;
    // Floor, ceiling, then the walls at -Z (back), +Z (front), -X, +X; all face inwards.
    add_quad(scene,
             {glm::vec3(a.x, a.y, a.z), glm::vec3(b.x, a.y, a.z), glm::vec3(b.x, a.y, b.z),
              glm::vec3(a.x, a.y, b.z)},
             glm::vec3(0, 1, 0), 0);
    add_quad(scene,
             {glm::vec3(a.x, b.y, a.z), glm::vec3(b.x, b.y, a.z), glm::vec3(b.x, b.y, b.z),
              glm::vec3(a.x, b.y, b.z)},
             glm::vec3(0, -1, 0), 0);
    add_quad(scene,
             {glm::vec3(a.x, a.y, a.z), glm::vec3(b.x, a.y, a.z), glm::vec3(b.x, b.y, a.z),
              glm::vec3(a.x, b.y, a.z)},
             glm::vec3(0, 0, 1), 0);
    add_quad(scene,
             {glm::vec3(a.x, a.y, b.z), glm::vec3(b.x, a.y, b.z), glm::vec3(b.x, b.y, b.z),
              glm::vec3(a.x, b.y, b.z)},
             glm::vec3(0, 0, -1), 0);
    add_quad(scene,
             {glm::vec3(a.x, a.y, a.z), glm::vec3(a.x, a.y, b.z), glm::vec3(a.x, b.y, b.z),
              glm::vec3(a.x, b.y, a.z)},
             glm::vec3(1, 0, 0), 0);
    add_quad(scene,
             {glm::vec3(b.x, a.y, a.z), glm::vec3(b.x, a.y, b.z), glm::vec3(b.x, b.y, b.z),
              glm::vec3(b.x, b.y, a.z)},
             glm::vec3(-1, 0, 0), 0);
    // Just inside the front wall, at eye height, looking at the far floor.
    scene.cameras.push_back(
        look_at("room", glm::vec3(0.0f, 1.6f, b.z - 0.2f), glm::vec3(0.0f, 0.9f, 0.0f), 1.0f));
    finish(scene);
    return scene;
}

namespace {

// An axis-aligned box of six outward-facing quads.
void add_box(Scene& scene, const glm::vec3& lo, const glm::vec3& hi, int material) {
    auto corner = [&](int x, int y, int z) {
        return glm::vec3(x ? hi.x : lo.x, y ? hi.y : lo.y, z ? hi.z : lo.z);
    };
    add_quad(scene, {corner(0, 0, 0), corner(1, 0, 0), corner(1, 0, 1), corner(0, 0, 1)},
             glm::vec3(0, -1, 0), material);
    add_quad(scene, {corner(0, 1, 0), corner(1, 1, 0), corner(1, 1, 1), corner(0, 1, 1)},
             glm::vec3(0, 1, 0), material);
    add_quad(scene, {corner(0, 0, 0), corner(1, 0, 0), corner(1, 1, 0), corner(0, 1, 0)},
             glm::vec3(0, 0, -1), material);
    add_quad(scene, {corner(0, 0, 1), corner(1, 0, 1), corner(1, 1, 1), corner(0, 1, 1)},
             glm::vec3(0, 0, 1), material);
    add_quad(scene, {corner(0, 0, 0), corner(0, 0, 1), corner(0, 1, 1), corner(0, 1, 0)},
             glm::vec3(-1, 0, 0), material);
    add_quad(scene, {corner(1, 0, 0), corner(1, 0, 1), corner(1, 1, 1), corner(1, 1, 0)},
             glm::vec3(1, 0, 0), material);
}

}  // namespace

Scene make_furnished_room_scene() {
    Scene scene = make_room_scene();
    scene.materials.push_back(diffuse(0.45f));
    const int furniture = int(scene.materials.size()) - 1;
    // A varnished floor and a brushed-steel cabinet: glossy lobes
    // (material_model.h) with highlights from the lights above them.
    Material varnish = diffuse(0.0f);
    varnish.base_color_factor = {0.45f, 0.36f, 0.28f, 1.0f};
    varnish.roughness = 0.35f;
    scene.materials.push_back(varnish);
    scene.meshes.front().material = int(scene.materials.size()) - 1;  // the floor quad
    Material steel = diffuse(0.0f);
    steel.base_color_factor = {0.75f, 0.75f, 0.78f, 1.0f};
    steel.metallic = 1.0f;
    steel.roughness = 0.55f;
    scene.materials.push_back(steel);
    const int cabinet = int(scene.materials.size()) - 1;
    // A table (top and four legs) in the middle of the floor.
    add_box(scene, {-1.2f, 0.72f, -0.8f}, {1.2f, 0.78f, 0.8f}, furniture);
    for (float x : {-1.1f, 1.02f}) {
        for (float z : {-0.7f, 0.62f})
            add_box(scene, {x, 0.0f, z}, {x + 0.08f, 0.72f, z + 0.08f}, furniture);
    }
    // Two pillars reaching the ceiling, a partition wall and a cabinet.
    add_box(scene, {-3.3f, 0.0f, -2.3f}, {-2.7f, 3.0f, -1.7f}, furniture);
    add_box(scene, {2.7f, 0.0f, -2.3f}, {3.3f, 3.0f, -1.7f}, furniture);
    add_box(scene, {-4.99f, 0.0f, 1.0f}, {-2.0f, 2.2f, 1.1f}, furniture);
    add_box(scene, {2.5f, 0.0f, -4.99f}, {4.5f, 1.4f, -4.3f}, cabinet);
    finish(scene);
    return scene;
}

namespace {

// A box turned by `angle` radians about the vertical through its centre:
// six outward-facing quads.
void add_turned_box(Scene& scene, const glm::vec3& center, const glm::vec3& half, float angle,
                    int material) {
    const float c = std::cos(angle), s = std::sin(angle);
    auto turn = [&](const glm::vec3& v) { return glm::vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z); };
    auto corner = [&](int x, int y, int z) {
        return center + turn(glm::vec3(x ? half.x : -half.x, y ? half.y : -half.y, z ? half.z : -half.z));
    };
    add_quad(scene, {corner(0, 0, 0), corner(1, 0, 0), corner(1, 0, 1), corner(0, 0, 1)},
             glm::vec3(0, -1, 0), material);
    add_quad(scene, {corner(0, 1, 0), corner(1, 1, 0), corner(1, 1, 1), corner(0, 1, 1)},
             glm::vec3(0, 1, 0), material);
    add_quad(scene, {corner(0, 0, 0), corner(1, 0, 0), corner(1, 1, 0), corner(0, 1, 0)},
             turn(glm::vec3(0, 0, -1)), material);
    add_quad(scene, {corner(0, 0, 1), corner(1, 0, 1), corner(1, 1, 1), corner(0, 1, 1)},
             turn(glm::vec3(0, 0, 1)), material);
    add_quad(scene, {corner(0, 0, 0), corner(0, 0, 1), corner(0, 1, 1), corner(0, 1, 0)},
             turn(glm::vec3(-1, 0, 0)), material);
    add_quad(scene, {corner(1, 0, 0), corner(1, 0, 1), corner(1, 1, 1), corner(1, 1, 0)},
             turn(glm::vec3(1, 0, 0)), material);
}

Material diffuse_rgb(glm::vec3 albedo) {
    Material m = diffuse(1.0f);
    m.base_color_factor = glm::vec4(albedo, 1.0f);
    return m;
}

}  // namespace

Scene make_cornell_emissive_scene() {
    Scene scene;
    scene.materials = {diffuse_rgb(kCornellWhite), diffuse_rgb(kCornellRed), diffuse_rgb(kCornellGreen)};
    Material panel = diffuse_rgb(kCornellWhite);
    panel.emissive_factor = kCornellPanelEmission;
    scene.materials.push_back(panel);
    const float h = kCornellSize / 2.0f, top = kCornellSize;
    auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 n, int material) {
        add_quad(scene, {a, b, c, d}, n, material);
    };
    // Floor, ceiling and back wall white; left red, right green; open at +Z.
    quad({-h, 0, -h}, {h, 0, -h}, {h, 0, h}, {-h, 0, h}, {0, 1, 0}, 0);
    quad({-h, top, -h}, {h, top, -h}, {h, top, h}, {-h, top, h}, {0, -1, 0}, 0);
    quad({-h, 0, -h}, {h, 0, -h}, {h, top, -h}, {-h, top, -h}, {0, 0, 1}, 0);
    quad({-h, 0, -h}, {-h, 0, h}, {-h, top, h}, {-h, top, -h}, {1, 0, 0}, 1);
    quad({h, 0, -h}, {h, 0, h}, {h, top, h}, {h, top, -h}, {-1, 0, 0}, 2);
    // The light: a panel just below the ceiling, facing down (Cornell's 130 x
    // 105 mm in a 555 mm box, scaled).
    const float px = kCornellSize * 130.0f / 555.0f / 2.0f, pz = kCornellSize * 105.0f / 555.0f / 2.0f;
    const float py = top - kCornellPanelGap;
    quad({-px, py, -pz}, {px, py, -pz}, {px, py, pz}, {-px, py, pz}, {0, -1, 0}, 3);
    // The short and the tall block, turned as in the original.
    const float unit = kCornellSize / 555.0f;
    add_turned_box(scene, glm::vec3(80.0f, 82.5f, 75.0f) * unit, glm::vec3(82.5f) * unit, -0.314f, 0);
    add_turned_box(scene, glm::vec3(-90.0f, 165.0f, -70.0f) * unit, glm::vec3(82.5f, 165.0f, 82.5f) * unit,
                   0.271f, 0);
    scene.cameras.push_back(look_at("cornell", glm::vec3(0.0f, h, kCornellSize * 1.9f),
                                    glm::vec3(0.0f, h, 0.0f), 0.68f));
    finish(scene);
    return scene;
}

Scene make_thesis_fig91_scene() {
    struct Entry {
        float x, y;
        float brightness;
        int r, g, b;
        const char* guid;
    };
    // SPEC §4 and the thesis's Figure 9.1 debug file (leaves, in order).
    constexpr std::array<Entry, 5> entries{{
        {-300.0f, 0.0f, 5000.0f, 255, 76, 216, "C2C14DFC4DDFAFF43D562F8AE934C28C"},
        {-225.0f, -45.0f, 7500.0f, 44, 255, 88, "E356FBF44AF8193168CEDA98FB01019F"},
        {-300.0f, 150.0f, 5000.0f, 125, 125, 20, "97D29E3844BB950A7C882BA48269BD84"},
        {0.0f, 0.0f, 5000.0f, 85, 59, 255, "EAC008644993E58FEA62588ABC2A6F1C"},
        {150.0f, 0.0f, 5000.0f, 255, 171, 123, "0688F64D490C83FDA87758910C4E7E39"},
    }};
    Scene scene;
    scene.materials.push_back(diffuse(0.8f));
    // The lights reach 200 units sideways at floor level (sqrt(250^2 - 150^2)).
    add_floor(scene, -600.0f, -450.0f, 450.0f, 350.0f, 0);
    for (const Entry& e : entries) {
        const glm::vec3 color(srgb_to_linear(e.r), srgb_to_linear(e.g), srgb_to_linear(e.b));
        scene.lights.push_back(point_light(from_thesis(e.x, e.y, 150.0f), e.brightness, 250.0f,
                                           color, *Guid::parse(e.guid)));
    }
    scene.cameras.push_back(look_at("thesis-fig91", glm::vec3(-75.0f, 850.0f, 800.0f),
                                    glm::vec3(-75.0f, 0.0f, -50.0f), 0.9f));
    finish(scene);
    return scene;
}

Scene make_thesis_test1_scene() {
    Scene scene;
    scene.materials.push_back(diffuse(0.8f));
    add_floor(scene, -900.0f, -800.0f, 1100.0f, 800.0f, 0);
    // Red and green 100 apart pair first; blue, 300 from green, joins at the root.
    scene.lights.push_back(point_light({-50.0f, 100.0f, 0.0f}, 5000.0f, 250.0f, {1, 0, 0},
                                       named_guid("thesis-test1/red")));
    scene.lights.push_back(point_light({50.0f, 100.0f, 0.0f}, 5000.0f, 250.0f, {0, 1, 0},
                                       named_guid("thesis-test1/green")));
    scene.lights.push_back(point_light({350.0f, 100.0f, 0.0f}, 5000.0f, 250.0f, {0, 0, 1},
                                       named_guid("thesis-test1/blue")));
    scene.cameras.push_back(look_at("thesis-test1", glm::vec3(100.0f, 1500.0f, 1100.0f),
                                    glm::vec3(100.0f, 0.0f, 0.0f), 0.9f));
    finish(scene);
    return scene;
}

Scene make_thesis_test2_scene() {
    Scene scene;
    scene.materials.push_back(diffuse(0.8f));
    add_floor(scene, -900.0f, -700.0f, 900.0f, 800.0f, 0);
    // Two pairs 100 apart and one single light, placed so that no two
    // distances tie: the pairs are plain to see, as in the thesis's Figure 9.7.
    struct Entry {
        glm::vec3 position;
        glm::vec3 color;
        const char* name;
    };
    const std::array<Entry, 5> entries{{
        {{-350.0f, 100.0f, -100.0f}, {1.0f, 0.8f, 0.2f}, "thesis-test2/a1"},
        {{-250.0f, 100.0f, -100.0f}, {1.0f, 0.3f, 0.1f}, "thesis-test2/a2"},
        {{250.0f, 100.0f, -120.0f}, {0.2f, 0.9f, 1.0f}, "thesis-test2/b1"},
        {{330.0f, 100.0f, -60.0f}, {0.3f, 0.3f, 1.0f}, "thesis-test2/b2"},
        {{40.0f, 100.0f, 270.0f}, {1.0f, 1.0f, 1.0f}, "thesis-test2/c"},
    }};
    for (const Entry& e : entries) {
        scene.lights.push_back(
            point_light(e.position, 5000.0f, 250.0f, e.color, named_guid(e.name)));
    }
    scene.cameras.push_back(look_at("thesis-test2", glm::vec3(0.0f, 1500.0f, 1200.0f),
                                    glm::vec3(0.0f, 0.0f, 0.0f), 0.9f));
    finish(scene);
    return scene;
}

std::vector<std::string> named_scene_names() {
    return {"room", "furnished-room", "cornell-emissive", "thesis-fig91", "thesis-test1", "thesis-test2"};
}

Result<Scene> make_named_scene(std::string_view name) {
    if (name == "room") return make_room_scene();
    if (name == "furnished-room") return make_furnished_room_scene();
    if (name == "cornell-emissive") return make_cornell_emissive_scene();
    if (name == "thesis-fig91") return make_thesis_fig91_scene();
    if (name == "thesis-test1") return make_thesis_test1_scene();
    if (name == "thesis-test2") return make_thesis_test2_scene();
    return make_error("unknown scene '" + std::string(name) +
                      "' (expected room, furnished-room, cornell-emissive, thesis-fig91, thesis-test1 or "
                      "thesis-test2)");
}

}  // namespace lc::client
