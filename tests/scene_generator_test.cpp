// Procedural scenes and light layouts: geometry facing the right way, the
// thesis's numbers, determinism, and errors for bad options.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightmass_server/builders/tree_builder.h"
#include "test_paths.h"
#include "tree_fixtures.h"

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
    const WalkTree tree = test::walk_tree(built->tree);
    std::set<uint32_t> cuts;
    for (float x = scene.bounds_min.x; x <= scene.bounds_max.x; x += 5.0f) {
        SurfacePoint p;
        p.position = glm::dvec3(x, 0.0, 0.0);
        const CutResult cut = shade_lightcuts(tree, {}, p, {CutCriterion::kRadius});
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


// --- Surface layout ----------------------------------------------------------------

LightLayoutOptions surface_options(const Scene& scene, uint32_t count, LightTypeChoice type,
                                   uint64_t seed = 0) {
    LightLayoutOptions o;
    o.count = count;
    o.layout = LightLayout::kSurface;
    o.type = type;
    o.seed = seed;
    o.box_min = scene.bounds_min;
    o.box_max = scene.bounds_max;
    o.surfaces = &scene;
    return o;
}

// A triangle as the test sees it: its front is the first vertex's stored
// normal, or the winding's normal when the mesh has none.
struct TestTriangle {
    glm::dvec3 a, b, c;
    glm::dvec3 front;
};

std::vector<TestTriangle> test_triangles(const Scene& scene) {
    std::vector<TestTriangle> out;
    for (const Mesh& mesh : scene.meshes) {
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            TestTriangle tri;
            tri.a = mesh.positions[mesh.indices[t]];
            tri.b = mesh.positions[mesh.indices[t + 1]];
            tri.c = mesh.positions[mesh.indices[t + 2]];
            const glm::dvec3 cross = glm::cross(tri.b - tri.a, tri.c - tri.a);
            if (glm::length(cross) == 0.0) continue;
            tri.front = mesh.normals.empty() ? glm::normalize(cross)
                                             : glm::dvec3(mesh.normals[mesh.indices[t]]);
            out.push_back(tri);
        }
    }
    return out;
}

// 1e-3 of the diagonal of the scene's geometry.
double expected_offset(const Scene& scene) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            lo = glm::min(lo, glm::dvec3(p));
            hi = glm::max(hi, glm::dvec3(p));
        }
    }
    return 1e-3 * glm::length(hi - lo);
}

// The triangle `p` stands in front of at height `offset` (1% tolerance),
// its foot inside the triangle; -1 if none.
int triangle_under(const std::vector<TestTriangle>& tris, const glm::dvec3& p, double offset) {
    for (size_t i = 0; i < tris.size(); ++i) {
        const TestTriangle& t = tris[i];
        const double height = glm::dot(p - t.a, t.front);
        if (std::abs(height - offset) > 0.01 * offset) continue;
        // Barycentric coordinates of the foot of p.
        const glm::dvec3 foot = p - height * t.front;
        const glm::dvec3 n = glm::cross(t.b - t.a, t.c - t.a);
        const double area2 = glm::dot(n, n);
        const double beta = glm::dot(glm::cross(foot - t.a, t.c - t.a), n) / area2;
        const double gamma = glm::dot(glm::cross(t.b - t.a, foot - t.a), n) / area2;
        const double eps = 1e-6;
        if (beta >= -eps && gamma >= -eps && beta + gamma <= 1.0 + eps) return int(i);
    }
    return -1;
}

TEST(SurfaceLayout, LightsStandJustInFrontOfTheRoomsSurfaces) {
    const Scene room = make_room_scene();
    const std::vector<TestTriangle> tris = test_triangles(room);
    ASSERT_EQ(tris.size(), 12u);
    const double offset = expected_offset(room);
    EXPECT_NEAR(offset, 1e-3 * std::sqrt(209.0), 1e-9);
    const uint32_t count = 3200;
    Result<std::vector<SceneLight>> lights =
        generate_lights(surface_options(room, count, LightTypeChoice::kMixed, 3));
    ASSERT_TRUE(lights.ok()) << lights.error();
    ASSERT_EQ(lights->size(), count);
    std::vector<int> per_quad(6, 0);
    std::set<Guid> guids;
    for (size_t i = 0; i < count; ++i) {
        const SceneLight& l = (*lights)[i];
        const int t = triangle_under(tris, glm::dvec3(l.position), offset);
        ASSERT_GE(t, 0) << "light " << i << " at (" << l.position.x << ", " << l.position.y
                        << ", " << l.position.z << ") is on no surface's front";
        ++per_quad[size_t(t / 2)];
        // Inside the room: the front of every wall faces in.
        EXPECT_TRUE(inside(l.position, kRoomMin, kRoomMax));
        EXPECT_EQ(l.type, i % 2 == 0 ? LightType::kPoint : LightType::kSpot);  // mixed
        EXPECT_EQ(l.intensity, kDefaultPointIntensity);
        if (l.type == LightType::kSpot) {
            const glm::dvec3 front = tris[size_t(t)].front;
            EXPECT_NEAR(l.direction.x, front.x, 1e-6);
            EXPECT_NEAR(l.direction.y, front.y, 1e-6);
            EXPECT_NEAR(l.direction.z, front.z, 1e-6);
            EXPECT_EQ(l.inner_cone_angle, 0.0f);
            EXPECT_EQ(l.outer_cone_angle, kHemisphereSpotOuter);
        }
        guids.insert(l.guid);
    }
    EXPECT_EQ(guids.size(), size_t(count));
    // Areas: floor and ceiling 100 each, every wall 30 (of 320 in all):
    // expected 1000, 1000 and 300 per wall; binomial sd <= 26.
    const int expected[6] = {1000, 1000, 300, 300, 300, 300};
    for (int q = 0; q < 6; ++q) EXPECT_NEAR(per_quad[size_t(q)], expected[q], 150) << "quad " << q;
}

TEST(SurfaceLayout, HemisphericalSpotsLightOnlyTheSideTheyFace) {
    const Scene room = make_room_scene();
    LightLayoutOptions o = surface_options(room, 1, LightTypeChoice::kSpot);
    o.box_min = {-5.0f, 2.9f, -5.0f};
    o.box_max = {5.0f, 3.1f, 5.0f};
    Result<std::vector<SceneLight>> spot = generate_lights(o);
    o.type = LightTypeChoice::kPoint;
    Result<std::vector<SceneLight>> point = generate_lights(o);
    ASSERT_TRUE(spot.ok() && point.ok());
    const glm::dvec3 at((*spot)[0].position);
    SurfacePoint ceiling;  // beside the light, on the ceiling it hangs from
    ceiling.position = glm::dvec3(at.x + 0.5, 3.0, at.z);
    ceiling.normal = {0.0, -1.0, 0.0};
    SurfacePoint floor;
    floor.position = glm::dvec3(at.x, 0.0, at.z);
    floor.normal = {0.0, 1.0, 0.0};
    EXPECT_EQ(shade_light((*spot)[0], ceiling), glm::dvec3(0.0));
    EXPECT_GT(shade_light((*point)[0], ceiling).x, 0.0);  // grazing, but lit
    // Straight below, the hemisphere's centre: as bright as the point light.
    const glm::dvec3 below_spot = shade_light((*spot)[0], floor);
    const glm::dvec3 below_point = shade_light((*point)[0], floor);
    EXPECT_GT(below_spot.x, 0.0);
    EXPECT_NEAR(below_spot.x, below_point.x, 1e-6 * below_point.x);
}

TEST(SurfaceLayout, PicksTrianglesByAreaAndPointsUniformly) {
    // Triangle A (area 1) has vertex normals against its winding, so its
    // front is -Y; triangle B (area 3) has no normals, so its front is the
    // winding's +Y. They sit side by side at y = 0.
    Scene scene;
    Mesh a;
    a.positions = {{0, 0, 0}, {0, 0, 2}, {1, 0, 0}};  // winding normal +Y
    a.normals.assign(3, glm::vec3(0, -1, 0));
    a.indices = {0, 1, 2};
    Mesh b;
    b.positions = {{3, 0, 0}, {3, 0, 2}, {6, 0, 0}};
    b.indices = {0, 1, 2};
    scene.meshes = {a, b};
    update_scene_bounds(scene);
    const double offset = expected_offset(scene);
    EXPECT_NEAR(offset, 1e-3 * std::sqrt(40.0), 1e-12);

    const uint32_t count = 40000;
    Result<std::vector<SceneLight>> lights =
        generate_lights(surface_options(scene, count, LightTypeChoice::kSpot, 11));
    ASSERT_TRUE(lights.ok()) << lights.error();
    int on_a = 0;
    // The medial subdivision of B into four triangles of equal area: corner
    // at (3,0), corner at (3,2), corner at (6,0), and the middle one.
    std::array<int, 4> quarters{};
    glm::dvec3 mean_b(0.0);
    for (const SceneLight& l : *lights) {
        const glm::dvec3 p(l.position);
        if (p.x < 2.0) {
            ++on_a;
            EXPECT_NEAR(p.y, -offset, 1e-9);
            EXPECT_EQ(l.direction, glm::vec3(0, -1, 0));
            EXPECT_GE(p.x, 0.0);
            EXPECT_GE(p.z, 0.0);
            EXPECT_LE(p.x + p.z / 2.0, 1.0 + 1e-6);
            continue;
        }
        EXPECT_NEAR(p.y, offset, 1e-9);
        EXPECT_EQ(l.direction, glm::vec3(0, 1, 0));
        // B in its own coordinates: u along x (0..3), v along z (0..2).
        const double u = (p.x - 3.0) / 3.0, v = p.z / 2.0;
        ASSERT_GE(u, -1e-6);
        ASSERT_GE(v, -1e-6);
        ASSERT_LE(u + v, 1.0 + 1e-6);
        const int quarter = u > 0.5 ? 2 : v > 0.5 ? 1 : u + v < 0.5 ? 0 : 3;
        ++quarters[size_t(quarter)];
        mean_b += p;
    }
    // Expected 10,000 on A (sd 87); uniform picking would give 20,000.
    EXPECT_NEAR(on_a, 10000, 500);
    const int on_b = int(count) - on_a;
    for (int q = 0; q < 4; ++q) {
        // Expected 7,500 each (sd 75).
        EXPECT_NEAR(quarters[size_t(q)], on_b / 4, 450) << "quarter " << q;
    }
    mean_b /= double(on_b);
    EXPECT_NEAR(mean_b.x, 4.0, 0.02);  // B's centroid (4, 0, 2/3)
    EXPECT_NEAR(mean_b.z, 2.0 / 3.0, 0.02);
}

TEST(SurfaceLayout, TheBoxSelectsTrianglesByCentroid) {
    const Scene room = make_room_scene();
    const double offset = expected_offset(room);
    LightLayoutOptions o = surface_options(room, 2000, LightTypeChoice::kSpot, 5);
    o.box_min = {-5.0f, 2.9f, -5.0f};  // the ceiling's centroids only
    o.box_max = {5.0f, 3.1f, 5.0f};
    Result<std::vector<SceneLight>> lights = generate_lights(o);
    ASSERT_TRUE(lights.ok()) << lights.error();
    glm::dvec3 mean(0.0);
    for (const SceneLight& l : *lights) {
        EXPECT_NEAR(l.position.y, 3.0 - offset, 1e-6);
        EXPECT_EQ(l.direction, glm::vec3(0, -1, 0));
        EXPECT_TRUE(inside(l.position, {-5, 0, -5}, {5, 3, 5}));
        mean += glm::dvec3(l.position) / 2000.0;
    }
    // Both triangles of the ceiling, over all of it (sd of the mean 0.065).
    EXPECT_NEAR(mean.x, 0.0, 0.3);
    EXPECT_NEAR(mean.z, 0.0, 0.3);

    // Half a floor: one of its two triangles has its centroid at x = 5/3.
    o.box_min = {0.0f, -0.1f, -5.0f};
    o.box_max = {5.0f, 0.1f, 5.0f};
    lights = generate_lights(o);
    ASSERT_TRUE(lights.ok()) << lights.error();
    for (const SceneLight& l : *lights) {
        EXPECT_NEAR(l.position.y, offset, 1e-6);
        EXPECT_GE(l.position.x - l.position.z, -1e-5) << "in the triangle below the diagonal";
    }
}

TEST(SurfaceLayout, DeterministicForASeedAndPositionsIndependentOfTheType) {
    const Scene room = make_furnished_room_scene();
    const auto a = generate_lights(surface_options(room, 300, LightTypeChoice::kSpot, 21));
    const auto b = generate_lights(surface_options(room, 300, LightTypeChoice::kSpot, 21));
    const auto c = generate_lights(surface_options(room, 300, LightTypeChoice::kSpot, 22));
    const auto d = generate_lights(surface_options(room, 300, LightTypeChoice::kPoint, 21));
    ASSERT_TRUE(a.ok() && b.ok() && c.ok() && d.ok());
    int same_as_other_seed = 0;
    for (size_t i = 0; i < 300; ++i) {
        EXPECT_EQ((*a)[i].position, (*b)[i].position);
        EXPECT_EQ((*a)[i].direction, (*b)[i].direction);
        EXPECT_EQ((*a)[i].guid, (*b)[i].guid);
        EXPECT_EQ((*a)[i].position, (*d)[i].position);
        if ((*a)[i].position == (*c)[i].position) ++same_as_other_seed;
    }
    EXPECT_EQ(same_as_other_seed, 0);
}

TEST(SurfaceLayout, HemisphericalSpotsSurviveAGltfRoundTrip) {
    Scene room = make_room_scene();
    LightLayoutOptions o = surface_options(room, 64, LightTypeChoice::kSpot, 1);
    o.range = 2.0f;
    o.intensity = 0.5f;
    o.classic = true;
    Result<std::vector<SceneLight>> lights = generate_lights(o);
    ASSERT_TRUE(lights.ok()) << lights.error();
    room.lights = *lights;
    const auto dir = lc::test::make_temp_dir("surface-lights");
    ASSERT_TRUE(write_scene_gltf(room, dir / "room.gltf").ok());
    Result<Scene> loaded = load_scene(dir / "room.gltf");
    ASSERT_TRUE(loaded.ok()) << loaded.error();  // the loader refuses outer > pi/2
    ASSERT_EQ(loaded->lights.size(), 64u);
    for (size_t i = 0; i < 64; ++i) {
        const SceneLight& l = loaded->lights[i];
        EXPECT_EQ(l.outer_cone_angle, kHemisphereSpotOuter);
        EXPECT_EQ(l.position, (*lights)[i].position);
        EXPECT_NEAR(glm::length(l.direction - (*lights)[i].direction), 0.0f, 1e-6f);
        EXPECT_EQ(l.range, 2.0f);
        EXPECT_EQ(l.intensity, 0.5f);
    }
    std::filesystem::remove_all(dir);
}

TEST(SurfaceLayout, RefusesWhatItCannotPlace) {
    const Scene room = make_room_scene();
    auto error_of = [](const LightLayoutOptions& o) {
        Result<std::vector<SceneLight>> r = generate_lights(o);
        return r.ok() ? std::string("(no error)") : r.error();
    };
    EXPECT_THAT(error_of(surface_options(room, 4, LightTypeChoice::kDirectional)),
                HasSubstr("directional lights have no position"));
    LightLayoutOptions middle = surface_options(room, 4, LightTypeChoice::kPoint);
    middle.box_min = {-1, 1, -1};
    middle.box_max = {1, 2, 1};
    EXPECT_THAT(error_of(middle), HasSubstr("no surface of the scene lies inside the box"));
    LightLayoutOptions no_scene = surface_options(room, 4, LightTypeChoice::kPoint);
    no_scene.surfaces = nullptr;
    EXPECT_THAT(error_of(no_scene), HasSubstr("needs the scene's triangles"));
    // The usual option checks come first.
    LightLayoutOptions inverted = surface_options(room, 4, LightTypeChoice::kPoint);
    inverted.box_min.x = 6.0f;
    EXPECT_THAT(error_of(inverted), HasSubstr("inverted on axis x"));

    // Only degenerate triangles: collinear and repeated vertices.
    Scene flat;
    Mesh line;
    line.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
    line.indices = {0, 1, 2, 0, 0, 1};
    flat.meshes.push_back(line);
    update_scene_bounds(flat);
    EXPECT_THAT(error_of(surface_options(flat, 4, LightTypeChoice::kPoint)),
                HasSubstr("no triangle with a non-zero area"));
    // A bad index names its mesh and triangle.
    Scene broken = flat;
    broken.meshes[0].indices = {0, 1, 7};
    EXPECT_THAT(error_of(surface_options(broken, 4, LightTypeChoice::kPoint)),
                HasSubstr("mesh 0, triangle 0 has vertex index 7 out of range"));
    broken.meshes[0].indices = {0, 1, 2};
    broken.meshes[0].positions[1].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THAT(error_of(surface_options(broken, 4, LightTypeChoice::kPoint)),
                HasSubstr("mesh 0, triangle 0 has a non-finite vertex position"));

    EXPECT_EQ(*parse_light_layout("surface"), LightLayout::kSurface);
    EXPECT_THAT(parse_light_layout("walls").error(), HasSubstr("random, grid or surface"));
}

TEST(SurfaceLayout, SkipsDegenerateTrianglesInTheBox) {
    Scene scene;
    Mesh mesh;
    // A sliver of zero area (its centroid in the box) and one real triangle.
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 0, 1}};
    mesh.normals.assign(6, glm::vec3(0, 0, 1));
    mesh.indices = {0, 1, 2, 3, 5, 4};
    scene.meshes.push_back(mesh);
    update_scene_bounds(scene);
    Result<std::vector<SceneLight>> lights =
        generate_lights(surface_options(scene, 500, LightTypeChoice::kPoint));
    ASSERT_TRUE(lights.ok()) << lights.error();
    const double offset = expected_offset(scene);
    for (const SceneLight& l : *lights) {
        EXPECT_NEAR(l.position.z, 1.0 + offset, 1e-6);  // on the real one, its +Z side
        EXPECT_FALSE(std::isnan(l.position.x));
    }
}

// A million units from the origin a float step (0.0625) exceeds the offset
// (0.0145): lights still stand in front of their surface, never on or behind it.
TEST(SurfaceLayout, StaysInFrontOfItsSurfaceFarFromTheOrigin) {
    Scene room = make_room_scene();
    const glm::vec3 shift(1e6f, 0.0f, -1e6f);
    for (Mesh& mesh : room.meshes) {
        for (glm::vec3& p : mesh.positions) p += shift;
    }
    update_scene_bounds(room);
    const double offset = expected_offset(room);
    Result<std::vector<SceneLight>> lights =
        generate_lights(surface_options(room, 2000, LightTypeChoice::kSpot, 4));
    ASSERT_TRUE(lights.ok()) << lights.error();
    const std::vector<TestTriangle> tris = test_triangles(room);
    for (const SceneLight& l : *lights) {
        // Its surface: the triangle whose normal it shines along, in whose plane's front it is.
        const glm::dvec3 p(l.position);
        double height = -1.0;
        for (const TestTriangle& t : tris) {
            if (glm::length(glm::dvec3(l.direction) - t.front) < 1e-6) {
                height = glm::dot(p - t.a, t.front);
                break;
            }
        }
        EXPECT_GE(height, 0.5 * offset);
        EXPECT_LE(height, 0.2);  // a few float steps at most
        EXPECT_TRUE(inside(l.position, kRoomMin + shift, kRoomMax + shift));
    }
}

// The random and grid layouts are as they were before the surface layout
// (values recorded from the earlier implementation, seed 7).
TEST(LightLayouts, RandomAndGridAreUnchanged) {
    const auto random =
        generate_lights(options(3, LightLayout::kRandom, LightTypeChoice::kMixed, 7));
    ASSERT_TRUE(random.ok()) << random.error();
    const glm::vec3 positions[3] = {{0x1.6c22a6p+0f, 0x1.b7171ap-3f, 0x1.c8afc6p+0f},
                                    {0x1.03390ep+0f, 0x1.286ef4p-1f, 0x1.96b616p+0f},
                                    {-0x1.145622p+0f, 0x1.33336ap-1f, -0x1.ea689ep+0f}};
    const glm::vec3 directions[3] = {{0.0f, -1.0f, 0.0f},
                                     {0x1.b7473ep-2f, -0x1.c23a1ap-1f, -0x1.a749eep-3f},
                                     {-0x1.799474p-1f, -0x1.3eed24p-1f, 0x1.0b4eecp-2f}};
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_EQ((*random)[i].position, positions[i]) << i;
        EXPECT_EQ((*random)[i].direction, directions[i]) << i;
    }
    const auto grid = generate_lights(options(5, LightLayout::kGrid, LightTypeChoice::kSpot, 7));
    ASSERT_TRUE(grid.ok()) << grid.error();
    const glm::vec3 cells[5] = {{-1, 0.5f, -2}, {1, 0.5f, -2}, {-1, 0.5f, 0}, {1, 0.5f, 0},
                                {-1, 0.5f, 2}};
    for (size_t i = 0; i < 5; ++i) EXPECT_EQ((*grid)[i].position, cells[i]) << i;
}

}  // namespace
}  // namespace lc::client
