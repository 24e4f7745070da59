// Procedural scenes and light layouts: geometry facing the right way, the
// thesis's numbers, determinism, and errors for bad options.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "editor_client/render/cpu_evaluator.h"
#include "editor_client/scene/gltf_loader.h"
#include "editor_client/scene/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "lightmass_server/tree_builder.h"
#include "test_paths.h"

namespace lc::client {
namespace {

using ::testing::HasSubstr;

bool inside(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
}

// Front faces (counter-clockwise) agree with the stored normals.
void expect_consistent_winding(const Mesh& mesh) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]];
        const glm::vec3 b = mesh.positions[mesh.indices[t + 1]];
        const glm::vec3 c = mesh.positions[mesh.indices[t + 2]];
        const glm::vec3 face = glm::cross(b - a, c - a);
        EXPECT_GT(glm::dot(face, mesh.normals[mesh.indices[t]]), 0.0f);
    }
}

TEST(RoomScene, SixInwardQuadsAndACameraInside) {
    const Scene room = make_room_scene();
    ASSERT_EQ(room.meshes.size(), 6u);
    const glm::vec3 center = (kRoomMin + kRoomMax) * 0.5f;
    for (const Mesh& quad : room.meshes) {
        ASSERT_EQ(quad.positions.size(), 4u);
        ASSERT_EQ(quad.indices.size(), 6u);
        for (size_t i = 0; i < 4; ++i) {
            EXPECT_GT(glm::dot(center - quad.positions[i], quad.normals[i]), 0.0f)
                << "faces inward";
            EXPECT_FLOAT_EQ(glm::length(quad.normals[i]), 1.0f);
        }
        expect_consistent_winding(quad);
        EXPECT_EQ(quad.material, 0);
    }
    ASSERT_EQ(room.materials.size(), 1u);
    EXPECT_EQ(room.materials[0].metallic, 0.0f);
    EXPECT_EQ(room.materials[0].base_color_factor, glm::vec4(0.7f, 0.7f, 0.7f, 1.0f));
    EXPECT_EQ(room.bounds_min, kRoomMin);
    EXPECT_EQ(room.bounds_max, kRoomMax);
    ASSERT_EQ(room.cameras.size(), 1u);
    EXPECT_TRUE(inside(room.cameras[0].eye, kRoomMin, kRoomMax));
    EXPECT_TRUE(inside(room.cameras[0].target, kRoomMin, kRoomMax));
    EXPECT_TRUE(room.lights.empty());
    EXPECT_TRUE(inside(kRoomLightBoxMin, kRoomMin, kRoomMax));
    EXPECT_TRUE(inside(kRoomLightBoxMax, kRoomMin, kRoomMax));
    EXPECT_FALSE(room.guid.is_zero());
}

TEST(ThesisScenes, Figure91HasTheThesissLightsAboveAFloor) {
    const Scene scene = make_thesis_fig91_scene();
    ASSERT_EQ(scene.lights.size(), 5u);
    // Thesis (x, y, 150) -> glTF (x, 150, -y).
    const glm::vec3 expected[5] = {
        {-300, 150, 0}, {-225, 150, 45}, {-300, 150, -150}, {0, 150, 0}, {150, 150, 0}};
    const float brightness[5] = {5000, 7500, 5000, 5000, 5000};
    const char* guids[5] = {"C2C14DFC4DDFAFF43D562F8AE934C28C", "E356FBF44AF8193168CEDA98FB01019F",
                            "97D29E3844BB950A7C882BA48269BD84", "EAC008644993E58FEA62588ABC2A6F1C",
                            "0688F64D490C83FDA87758910C4E7E39"};
    for (int i = 0; i < 5; ++i) {
        const SceneLight& l = scene.lights[size_t(i)];
        EXPECT_EQ(l.type, LightType::kPoint);
        EXPECT_EQ(l.position, expected[i]);
        EXPECT_EQ(l.intensity, brightness[i]);
        EXPECT_EQ(l.range, 250.0f);
        EXPECT_EQ(l.guid.to_hex(), guids[i]);
    }
    // The thesis's first pair: radius 250 + |A - B| = 337.464.
    EXPECT_NEAR(250.0 + glm::length(glm::dvec3(expected[0] - expected[1])), 337.464, 1e-3);
    // The floor at y = 0 reaches past every light's reach on the floor (200 sideways).
    ASSERT_EQ(scene.meshes.size(), 1u);
    for (const SceneLight& l : scene.lights) {
        EXPECT_LE(scene.bounds_min.x, l.position.x - 200.0f);
        EXPECT_GE(scene.bounds_max.x, l.position.x + 200.0f);
        EXPECT_LE(scene.bounds_min.z, l.position.z - 200.0f);
        EXPECT_GE(scene.bounds_max.z, l.position.z + 200.0f);
    }
    EXPECT_EQ(scene.meshes[0].normals[0], glm::vec3(0, 1, 0));
    expect_consistent_winding(scene.meshes[0]);
    ASSERT_EQ(scene.cameras.size(), 1u);
    EXPECT_GT(scene.cameras[0].eye.y, 150.0f);
}

// With the thesis's representative rule the server reproduces Figure 9.1:
// clusters 12500 (r 337.464), 10000 (r 400), 17500 (r 400), root 27500 (r 700).
TEST(ThesisScenes, Figure91BuildsTheThesissTree) {
    const Scene scene = make_thesis_fig91_scene();
    bake::BuildOptions options;
    options.representative_rule = RepresentativeRule::kThesisFirst;
    Result<bake::BuildResult> built = bake::build_light_tree(
        scene.lights, options, [](std::string_view, double) { return true; });
    ASSERT_TRUE(built.ok()) << built.error();
    const LightTree& tree = built->tree;
    ASSERT_EQ(tree.nodes.size(), 9u);
    EXPECT_EQ(tree.nodes[0].brightness, 27500.0f);
    EXPECT_NEAR(tree.nodes[0].radius, 700.0f, 1e-3f);
    std::multiset<std::pair<int, int>> clusters;  // (brightness, radius x 1000)
    for (const LightTreeNode& n : tree.nodes) {
        if (!n.is_leaf()) clusters.insert({int(n.brightness), int(std::lround(n.radius * 1000.0))});
    }
    const std::multiset<std::pair<int, int>> expected{
        {27500, 700000}, {17500, 400000}, {12500, 337464}, {10000, 400000}};
    EXPECT_EQ(clusters, expected);
}

TEST(ThesisScenes, Test1ShowsThreeRadiusCutsOnTheFloor) {
    const Scene scene = make_thesis_test1_scene();
    ASSERT_EQ(scene.lights.size(), 3u);
    const glm::vec3 r = scene.lights[0].position, g = scene.lights[1].position,
                    b = scene.lights[2].position;
    EXPECT_EQ(scene.lights[0].color, glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.lights[1].color, glm::vec3(0, 1, 0));
    EXPECT_EQ(scene.lights[2].color, glm::vec3(0, 0, 1));
    EXPECT_LT(glm::length(r - g), glm::length(g - b));
    EXPECT_LT(glm::length(r - g), glm::length(r - b));
    for (const SceneLight& l : scene.lights) EXPECT_GT(l.range, 0.0f);

    bake::BuildOptions options;
    options.representative_rule = RepresentativeRule::kThesisFirst;
    Result<bake::BuildResult> built = bake::build_light_tree(
        scene.lights, options, [](std::string_view, double) { return true; });
    ASSERT_TRUE(built.ok()) << built.error();
    // Walk across the floor: the radius criterion picks exactly three different cuts.
    std::set<uint32_t> cuts;
    for (float x = scene.bounds_min.x; x <= scene.bounds_max.x; x += 5.0f) {
        SurfacePoint p;
        p.position = glm::dvec3(x, 0.0, 0.0);
        const CutResult cut = shade_lightcuts(built->tree, {}, p, {CutCriterion::kRadius});
        cuts.insert(cut.cut_hash);
    }
    EXPECT_EQ(cuts.size(), 3u);
}

TEST(ThesisScenes, Test2HasTwoClearPairsAndNoTies) {
    const Scene scene = make_thesis_test2_scene();
    ASSERT_EQ(scene.lights.size(), 5u);
    std::set<float> distances;
    std::vector<float> all;
    for (size_t i = 0; i < 5; ++i) {
        for (size_t j = i + 1; j < 5; ++j) {
            const float d = glm::length(scene.lights[i].position - scene.lights[j].position);
            distances.insert(d);
            all.push_back(d);
        }
    }
    EXPECT_FLOAT_EQ(glm::length(scene.lights[0].position - scene.lights[1].position), 100.0f);
    EXPECT_FLOAT_EQ(glm::length(scene.lights[2].position - scene.lights[3].position), 100.0f);
    // Every other distance is much larger, so the first pairing is plain to see.
    std::sort(all.begin(), all.end());
    EXPECT_GT(all[2], 300.0f);
    EXPECT_EQ(distances.size(), 9u);  // only the two pairs' 100 coincide
    // Cluster positions are their representatives': whichever light represents
    // each pair, the single light is never equally far from both pairs.
    for (int a : {0, 1})
        for (int b : {2, 3})
            EXPECT_NE(glm::length(scene.lights[4].position - scene.lights[size_t(a)].position),
                      glm::length(scene.lights[4].position - scene.lights[size_t(b)].position));
}

TEST(NamedScenes, AllWriteAndLoad) {
    const auto dir = lc::test::make_temp_dir("named-scenes");
    for (const std::string& name : named_scene_names()) {
        Result<Scene> scene = make_named_scene(name);
        ASSERT_TRUE(scene.ok()) << scene.error();
        ASSERT_TRUE(write_scene_gltf(*scene, dir / (name + ".gltf")).ok());
        Result<Scene> loaded = load_scene(dir / (name + ".gltf"));
        ASSERT_TRUE(loaded.ok()) << loaded.error();
        EXPECT_EQ(loaded->lights.size(), scene->lights.size());
        EXPECT_EQ(loaded->meshes.size(), scene->meshes.size());
        EXPECT_EQ(loaded->cameras.size(), 1u);
    }
    Result<Scene> unknown = make_named_scene("cathedral");
    ASSERT_FALSE(unknown.ok());
    EXPECT_THAT(unknown.error(), HasSubstr("unknown scene 'cathedral'"));
    EXPECT_THAT(unknown.error(), HasSubstr("thesis-fig91"));
    std::filesystem::remove_all(dir);
}

// --- Light layouts -----------------------------------------------------------------

LightLayoutOptions options(uint32_t count, LightLayout layout, LightTypeChoice type,
                           uint64_t seed = 0) {
    LightLayoutOptions o;
    o.count = count;
    o.layout = layout;
    o.type = type;
    o.seed = seed;
    o.box_min = {-2, 0, -3};
    o.box_max = {2, 1, 3};
    return o;
}

TEST(LightLayouts, RandomIsDeterministicInsideTheBoxAndSeedDependent) {
    const auto a = generate_lights(options(500, LightLayout::kRandom, LightTypeChoice::kMixed, 7));
    const auto b = generate_lights(options(500, LightLayout::kRandom, LightTypeChoice::kMixed, 7));
    const auto c = generate_lights(options(500, LightLayout::kRandom, LightTypeChoice::kMixed, 8));
    ASSERT_TRUE(a.ok() && b.ok() && c.ok());
    ASSERT_EQ(a->size(), 500u);
    std::set<Guid> guids;
    int same_position = 0;
    for (size_t i = 0; i < 500; ++i) {
        const SceneLight& l = (*a)[i];
        EXPECT_EQ(l.position, (*b)[i].position);
        EXPECT_EQ(l.direction, (*b)[i].direction);
        EXPECT_EQ(l.guid, (*b)[i].guid);
        if (l.position == (*c)[i].position) ++same_position;
        EXPECT_TRUE(inside(l.position, {-2, 0, -3}, {2, 1, 3}));
        EXPECT_EQ(l.type, LightType(i % 3));  // mixed: point, spot, directional in turn
        EXPECT_NEAR(glm::length(l.direction), 1.0f, 1e-6f);
        const float down = -l.direction.y;
        if (l.type == LightType::kSpot) {
            EXPECT_GE(down, std::cos(float(std::numbers::pi / 6)) - 1e-6f);
            EXPECT_EQ(l.inner_cone_angle, kGeneratedSpotInner);
            EXPECT_EQ(l.outer_cone_angle, kGeneratedSpotOuter);
        }
        if (l.type == LightType::kDirectional) {
            EXPECT_GE(down, std::cos(float(std::numbers::pi / 3)) - 1e-6f);
            EXPECT_EQ(l.intensity, kDefaultDirectionalIntensity);
        } else {
            EXPECT_EQ(l.intensity, kDefaultPointIntensity);
        }
        guids.insert(l.guid);
    }
    EXPECT_EQ(guids.size(), 500u);
    EXPECT_EQ(same_position, 0);
    // The positions spread over the whole box (mean near the centre).
    glm::dvec3 mean(0.0);
    for (const SceneLight& l : *a) mean += glm::dvec3(l.position) / 500.0;
    EXPECT_NEAR(mean.x, 0.0, 0.2);
    EXPECT_NEAR(mean.y, 0.5, 0.05);
    EXPECT_NEAR(mean.z, 0.0, 0.3);
}

TEST(LightLayouts, GridFillsCellCentres) {
    LightLayoutOptions o = options(27, LightLayout::kGrid, LightTypeChoice::kSpot);
    o.box_min = {0, 0, 0};
    o.box_max = {3, 3, 3};
    o.intensity = 2.5f;
    o.range = 4.0f;
    o.classic = true;
    Result<std::vector<SceneLight>> grid = generate_lights(o);
    ASSERT_TRUE(grid.ok()) << grid.error();
    std::set<std::tuple<float, float, float>> cells;
    for (const SceneLight& l : *grid) {
        cells.insert({l.position.x, l.position.y, l.position.z});
        for (int a = 0; a < 3; ++a) {
            const float frac = l.position[a] - std::floor(l.position[a]);
            EXPECT_FLOAT_EQ(frac, 0.5f);  // cell centres of a 3x3x3 grid
        }
        EXPECT_EQ(l.direction, glm::vec3(0, -1, 0));
        EXPECT_EQ(l.intensity, 2.5f);
        EXPECT_EQ(l.range, 4.0f);
        EXPECT_TRUE(l.classic);
    }
    EXPECT_EQ(cells.size(), 27u);
    // The first lights fill one horizontal layer (x, then z).
    EXPECT_EQ((*grid)[0].position, glm::vec3(0.5f, 0.5f, 0.5f));
    EXPECT_EQ((*grid)[1].position, glm::vec3(1.5f, 0.5f, 0.5f));
    EXPECT_EQ((*grid)[3].position, glm::vec3(0.5f, 0.5f, 1.5f));

    // A flat box: every light at the same height, in a 10 x 5 grid of a 20 x 10 area.
    o.count = 50;
    o.box_min = {0, 2, 0};
    o.box_max = {20, 2, 10};
    Result<std::vector<SceneLight>> flat = generate_lights(o);
    ASSERT_TRUE(flat.ok()) << flat.error();
    std::set<float> xs, zs;
    for (const SceneLight& l : *flat) {
        EXPECT_EQ(l.position.y, 2.0f);
        xs.insert(l.position.x);
        zs.insert(l.position.z);
    }
    EXPECT_EQ(xs.size(), 10u);
    EXPECT_EQ(zs.size(), 5u);
}

TEST(LightLayouts, BadOptionsAreRejectedWithTheirName) {
    struct Case {
        LightLayoutOptions o;
        const char* message;
    };
    std::vector<Case> cases;
    auto base = [] { return options(4, LightLayout::kRandom, LightTypeChoice::kPoint); };
    cases.push_back({base(), ""});
    cases.back().o.count = 0;
    cases.back().message = "at least 1";
    cases.push_back({base(), "inverted on axis y"});
    cases.back().o.box_min.y = 5.0f;
    cases.push_back({base(), "non-finite"});
    cases.back().o.box_max.x = std::numeric_limits<float>::infinity();
    cases.push_back({base(), "intensity"});
    cases.back().o.intensity = -1.0f;
    cases.push_back({base(), "range"});
    cases.back().o.range = std::numeric_limits<float>::quiet_NaN();
    for (const Case& c : cases) {
        Result<std::vector<SceneLight>> r = generate_lights(c.o);
        ASSERT_FALSE(r.ok()) << c.message;
        EXPECT_THAT(r.error(), HasSubstr(c.message));
    }
    EXPECT_THAT(parse_light_layout("spiral").error(), HasSubstr("unknown light layout 'spiral'"));
    EXPECT_THAT(parse_light_type_choice("area").error(), HasSubstr("unknown light type 'area'"));
    EXPECT_EQ(*parse_light_type_choice("mixed"), LightTypeChoice::kMixed);
    EXPECT_EQ(*parse_light_layout("grid"), LightLayout::kGrid);
}

TEST(LightLayouts, SaltSeparatesGuidsOfTwoAdditions) {
    LightLayoutOptions o = options(8, LightLayout::kGrid, LightTypeChoice::kPoint);
    const auto first = generate_lights(o);
    o.guid_salt = Guid{1, 2, 3, 4};
    const auto second = generate_lights(o);
    ASSERT_TRUE(first.ok() && second.ok());
    for (size_t i = 0; i < 8; ++i) {
        EXPECT_EQ((*first)[i].position, (*second)[i].position);
        EXPECT_NE((*first)[i].guid, (*second)[i].guid);
    }
}

}  // namespace
}  // namespace lc::client
