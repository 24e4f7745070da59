#pragma once
// Procedural scenes and light layouts, deterministic for a given seed.
//
// Axes: glTF's, right-handed with +Y up; floors lie in the XZ plane at y = 0.
// The thesis's figures use +Z up with the lights at z = 150; we map a thesis
// point (x, y, z) to glTF (x, z, -y), a rotation, so distances, radii and the
// trees built from them are the thesis's.
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lightcuts/scene.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"

namespace lc::client {

enum class LightLayout : uint8_t { kRandom = 0, kGrid = 1, kSurface = 2 };
enum class LightTypeChoice : uint8_t { kPoint = 0, kSpot = 1, kDirectional = 2, kMixed = 3 };

Result<LightLayout> parse_light_layout(std::string_view text);
Result<LightTypeChoice> parse_light_type_choice(std::string_view text);

// Intensities used when none is given: candela for point and spot lights,
// lux for directional lights (a 10 cd bulb 2 m away gives 2.5 lux).
inline constexpr float kDefaultPointIntensity = 10.0f;
inline constexpr float kDefaultDirectionalIntensity = 1.0f;
// Spot cones of generated spot lights (radians).
inline constexpr float kGeneratedSpotInner = 0.25f;
inline constexpr float kGeneratedSpotOuter = 0.7853982f;  // pi/4
// Spots of the surface layout are hemispherical emitters: inner cone 0, outer
// cone glTF's largest, pi/2. The largest float not above pi/2, because the
// float nearest pi/2 is above it and the glTF loader (in double) refuses it.
inline constexpr float kHemisphereSpotOuter = 1.57079625f;
static_assert(double(kHemisphereSpotOuter) <= std::numbers::pi / 2.0 &&
              std::numbers::pi / 2.0 - double(kHemisphereSpotOuter) < 1e-7);
// Surface lights sit this fraction of the scene's diagonal in front of their surface.
inline constexpr double kSurfaceLightOffset = 1e-3;

struct LightLayoutOptions {
    uint32_t count = 16;
    LightLayout layout = LightLayout::kRandom;
    uint64_t seed = 0;
    LightTypeChoice type = LightTypeChoice::kPoint;  // mixed: point, spot, directional in turn
    glm::vec3 box_min{-1.0f};
    glm::vec3 box_max{1.0f};
    std::optional<float> intensity;  // absent: the per-type defaults above
    float range = 0.0f;              // 0: unbounded
    bool classic = false;
    // Mixed into the generated GUIDs (add-lights passes the scene's GUID), so
    // adding to a scene twice with one seed still gives distinct GUIDs.
    Guid guid_salt;
    // The scene whose triangles the surface layout samples (must outlive the
    // call); unused by the random and grid layouts.
    const Scene* surfaces = nullptr;
};

// Random: uniform in the box, spots aimed down within 30 degrees, directional
// lights down within 60 degrees. Grid: cell centres of the most cubic grid of
// at least `count` cells that fits the box, filled in x, then z, then y order;
// spots and directional lights aim straight down (-Y).
// Surface: on the triangles of `options.surfaces` whose centroid lies in the
// box (zero-area ones skipped), area-weighted, each light moved
// kSurfaceLightOffset x the scene's diagonal along the triangle's geometric
// normal, to the side its shading normal faces. Spots are hemispherical
// emitters aimed along that normal; mixed is point and spot in turn;
// directional lights are refused (they have no position on a surface).
Result<std::vector<SceneLight>> generate_lights(const LightLayoutOptions& options);

// The empty room: floor, ceiling and four walls as inward-facing quads,
// diffuse grey, a camera looking in from the front wall.
inline constexpr glm::vec3 kRoomMin{-5.0f, 0.0f, -5.0f};
inline constexpr glm::vec3 kRoomMax{5.0f, 3.0f, 5.0f};
// Where add-lights puts lights in the room by default: inside it, 0.3 from
// every surface.
inline constexpr glm::vec3 kRoomLightBoxMin{-4.7f, 0.3f, -4.7f};
inline constexpr glm::vec3 kRoomLightBoxMax{4.7f, 2.7f, 4.7f};
Scene make_room_scene();
// The room with furniture that casts shadows: a table, two pillars and a
// partition wall (darker diffuse), a brushed-steel cabinet, and a varnished
// floor (glossy, material_model.h).
Scene make_furnished_room_scene();

// The Cornell box lit only by an emissive ceiling panel (no punctual light):
// its published reflectances, a 2 m box open at +Z, two turned blocks, and a
// panel of Cornell's proportions kCornellPanelGap below the ceiling.
inline constexpr float kCornellSize = 2.0f;
inline constexpr float kCornellPanelGap = 0.005f;
inline constexpr glm::vec3 kCornellWhite{0.73f, 0.73f, 0.73f};
inline constexpr glm::vec3 kCornellRed{0.63f, 0.065f, 0.05f};
inline constexpr glm::vec3 kCornellGreen{0.14f, 0.45f, 0.091f};
inline constexpr glm::vec3 kCornellPanelEmission{17.0f, 12.0f, 4.0f};
Scene make_cornell_emissive_scene();

// Thesis Figure 9.1: five point lights of radius (range) 250 at height 150
// above a floor, with the thesis's positions, brightness, colours and GUIDs.
Scene make_thesis_fig91_scene();
// Thesis Test 1: red and green lights close together, blue farther away,
// range 250, so the radius criterion shows three cuts on the floor.
Scene make_thesis_test1_scene();
// Thesis Test 2: five lights in two close pairs and one single light.
Scene make_thesis_test2_scene();

// "room", "furnished-room", "cornell-emissive", "thesis-fig91", "thesis-test1", "thesis-test2".
std::vector<std::string> named_scene_names();
Result<Scene> make_named_scene(std::string_view name);

}  // namespace lc::client
