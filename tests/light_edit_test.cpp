// Adding and removing lights, in the library and through editor_client's
// add-lights / remove-lights / make-scene commands.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/light_edit.h"
#include "editor_client/scene/scene_generator.h"
#include "editor_client/scene/inputs/scene_guid.h"
#include "test_paths.h"

namespace lc::client {
namespace {

using ::testing::HasSubstr;

SceneLight light_at(glm::vec3 position, uint32_t id) {
    SceneLight l;
    l.guid = Guid{7, 7, 7, id};
    l.position = position;
    return l;
}

Scene room_with_lights(int count) {
    Scene scene = make_room_scene();
    std::vector<SceneLight> lights;
    for (int i = 0; i < count; ++i)
        lights.push_back(light_at({float(i) * 0.5f - 2.0f, 2, 0}, uint32_t(i + 1)));
    EXPECT_TRUE(add_lights(scene, lights).ok());
    return scene;
}

TEST(AddLights, AppendsAndRefreshesBoundsAndGuid) {
    Scene scene = make_room_scene();
    const Guid before = scene.guid;
    std::vector<SceneLight> lights{light_at({0, 10, 0}, 1), light_at({1, 1, 1}, 2)};
    ASSERT_TRUE(add_lights(scene, lights).ok());
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.bounds_max.y, 10.0f);  // the light above the room extends the bounds
    EXPECT_NE(scene.guid, before);
    EXPECT_EQ(scene.guid, compute_scene_guid(scene));
}

TEST(AddLights, RejectsInvalidLightsAndLeavesTheSceneUnchanged) {
    Scene scene = room_with_lights(2);
    const Scene original = scene;
    struct Case {
        SceneLight light;
        const char* message;
    };
    std::vector<Case> cases;
    cases.push_back({light_at({std::numeric_limits<float>::quiet_NaN(), 0, 0}, 50), "position"});
    cases.push_back({light_at({0, 0, 0}, 51), "intensity"});
    cases.back().light.intensity = -3.0f;
    cases.push_back({light_at({0, 0, 0}, 52), "cone"});
    cases.back().light.type = LightType::kSpot;
    cases.back().light.inner_cone_angle = 0.9f;
    cases.back().light.outer_cone_angle = 0.3f;
    cases.push_back({light_at({0, 0, 0}, 1), "already in the scene"});
    cases.push_back({light_at({0, 0, 0}, 0), "GUID is zero"});
    cases.back().light.guid = Guid{};
    for (const Case& c : cases) {
        std::vector<SceneLight> batch{light_at({0, 1, 0}, 99), c.light};
        Status status = add_lights(scene, batch);
        ASSERT_FALSE(status.ok()) << c.message;
        EXPECT_THAT(status.error(), HasSubstr(c.message));
        EXPECT_THAT(status.error(), HasSubstr("light 3"));  // its index once added
        EXPECT_EQ(scene.lights.size(), original.lights.size());
        EXPECT_EQ(scene.guid, original.guid);
    }
    // Two new lights with one GUID.
    std::vector<SceneLight> twins{light_at({0, 1, 0}, 60), light_at({0, 2, 0}, 60)};
    EXPECT_THAT(add_lights(scene, twins).error(), HasSubstr("already in the scene"));
}

TEST(RemoveLights, ByIndexKeepsTheOrderOfTheRest) {
    Scene scene = room_with_lights(5);
    const std::vector<size_t> indices{3, 0};
    ASSERT_TRUE(remove_lights_by_index(scene, indices).ok());
    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.lights[0].guid.d, 2u);
    EXPECT_EQ(scene.lights[1].guid.d, 3u);
    EXPECT_EQ(scene.lights[2].guid.d, 5u);
    EXPECT_EQ(scene.guid, compute_scene_guid(scene));

    const Scene before = scene;
    const std::vector<size_t> out_of_range{1, 3};
    Status status = remove_lights_by_index(scene, out_of_range);
    ASSERT_FALSE(status.ok());
    EXPECT_THAT(status.error(),
                HasSubstr("cannot remove light 3: the scene has 3 lights (indices 0 to 2)"));
    EXPECT_EQ(scene.lights.size(), 3u);  // nothing removed
    const std::vector<size_t> twice{1, 1};
    EXPECT_THAT(remove_lights_by_index(scene, twice).error(), HasSubstr("given twice"));
    EXPECT_EQ(scene.guid, before.guid);
}

TEST(RemoveLights, ByGuidAndAll) {
    Scene scene = room_with_lights(4);
    const std::vector<Guid> guids{Guid{7, 7, 7, 2}, Guid{7, 7, 7, 4}};
    ASSERT_TRUE(remove_lights_by_guid(scene, guids).ok());
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[1].guid.d, 3u);
    const std::vector<Guid> unknown{Guid{1, 1, 1, 1}};
    Status status = remove_lights_by_guid(scene, unknown);
    ASSERT_FALSE(status.ok());
    EXPECT_THAT(status.error(), HasSubstr(Guid{1, 1, 1, 1}.to_hex()));
    EXPECT_THAT(status.error(), HasSubstr("no light of the scene has this GUID"));
    remove_all_lights(scene);
    EXPECT_TRUE(scene.lights.empty());
    EXPECT_EQ(scene.bounds_max, kRoomMax);
    EXPECT_EQ(scene.guid, make_room_scene().guid);  // back to the empty room
}

TEST(ParseLists, IndicesAndGuids) {
    EXPECT_EQ(*parse_index_list("4"), (std::vector<size_t>{4}));
    EXPECT_EQ(*parse_index_list("1, 2,30"), (std::vector<size_t>{1, 2, 30}));
    EXPECT_THAT(parse_index_list("1,x").error(), HasSubstr("'x' is not a light index"));
    EXPECT_THAT(parse_index_list("-1").error(), HasSubstr("'-1' is not a light index"));
    EXPECT_THAT(parse_index_list("1,,2").error(), HasSubstr("'' is not a light index"));
    Result<std::vector<Guid>> guids =
        parse_guid_list("C2C14DFC4DDFAFF43D562F8AE934C28C,e356fbf4-4af81931-68ceda98-fb01019f");
    ASSERT_TRUE(guids.ok()) << guids.error();
    ASSERT_EQ(guids->size(), 2u);
    EXPECT_EQ((*guids)[1].to_hex(), "E356FBF44AF8193168CEDA98FB01019F");
    EXPECT_THAT(parse_guid_list("123").error(), HasSubstr("'123' is not a GUID"));
}

// --- The commands -------------------------------------------------------------------

struct CommandRun {
    int exit_code = -1;
    std::string output;  // stdout and stderr
};

CommandRun run_client(const std::string& args, const std::filesystem::path& dir) {
    const auto log = dir / "command.log";
    const std::string command = (lc::test::bin_dir() / "editor_client").string() + " " + args +
                                " > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    CommandRun run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    run.output = text.str();
    return run;
}

std::string file_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

class LightEditCommands : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = lc::test::make_temp_dir("light-commands");
        if (!std::filesystem::exists(lc::test::bin_dir() / "editor_client"))
            GTEST_SKIP() << "editor_client is not built";
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const char* name) const { return (dir_ / name).string(); }
    std::filesystem::path dir_;
};

TEST_F(LightEditCommands, AddToTheRoomThenRemove) {
    CommandRun r = run_client(
        "add-lights --count 12 --layout grid --type mixed --range 5 -o " + path("a.gltf"), dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr("12 lights in total"));
    Result<Scene> a = load_scene(dir_ / "a.gltf");
    ASSERT_TRUE(a.ok()) << a.error();
    ASSERT_EQ(a->lights.size(), 12u);
    EXPECT_EQ(a->meshes.size(), 6u);  // the room
    for (const SceneLight& l : a->lights) {
        if (l.type != LightType::kDirectional) {
            EXPECT_TRUE(l.position.x >= kRoomLightBoxMin.x && l.position.x <= kRoomLightBoxMax.x);
            EXPECT_TRUE(l.position.y >= kRoomLightBoxMin.y && l.position.y <= kRoomLightBoxMax.y);
            EXPECT_EQ(l.range, 5.0f);
        }
    }
    // The same command twice writes the same bytes.
    r = run_client(
        "add-lights --count 12 --layout grid --type mixed --range 5 -o " + path("b.gltf"), dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(file_text(dir_ / "a.gltf"), file_text(dir_ / "b.gltf"));

    // Add to an existing scene (as .glb), with a seed and a box.
    r = run_client("add-lights " + path("a.gltf") +
                       " --count 5 --layout random --seed 9 --type spot --box -1,1,-1,1,2,1 "
                       "--intensity 40 --classic -o " +
                       path("c.glb"),
                   dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    Result<Scene> c = load_scene(dir_ / "c.glb");
    ASSERT_TRUE(c.ok()) << c.error();
    ASSERT_EQ(c->lights.size(), 17u);
    for (size_t i = 0; i < 12; ++i) EXPECT_EQ(c->lights[i].guid, a->lights[i].guid);
    for (size_t i = 12; i < 17; ++i) {
        const SceneLight& l = c->lights[i];
        EXPECT_EQ(l.type, LightType::kSpot);
        EXPECT_EQ(l.intensity, 40.0f);
        EXPECT_TRUE(l.classic);
        EXPECT_TRUE(l.position.x >= -1 && l.position.x <= 1 && l.position.y >= 1 &&
                    l.position.y <= 2);
    }

    // Remove by index, then by GUID, then all.
    r = run_client("remove-lights " + path("c.glb") + " --index 0,16 -o " + path("d.gltf"), dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    Result<Scene> d = load_scene(dir_ / "d.gltf");
    ASSERT_TRUE(d.ok()) << d.error();
    ASSERT_EQ(d->lights.size(), 15u);
    EXPECT_EQ(d->lights[0].guid, c->lights[1].guid);
    r = run_client("remove-lights " + path("d.gltf") + " --guid " + c->lights[5].guid.to_hex() +
                       " -o " + path("e.gltf"),
                   dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    Result<Scene> e = load_scene(dir_ / "e.gltf");
    ASSERT_TRUE(e.ok()) << e.error();
    ASSERT_EQ(e->lights.size(), 14u);
    for (const SceneLight& l : e->lights) EXPECT_NE(l.guid, c->lights[5].guid);
    r = run_client("remove-lights " + path("e.gltf") + " --all -o " + path("f.gltf"), dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    Result<Scene> f = load_scene(dir_ / "f.gltf");
    ASSERT_TRUE(f.ok()) << f.error();
    EXPECT_TRUE(f->lights.empty());
    EXPECT_EQ(f->meshes.size(), 6u);
}

TEST_F(LightEditCommands, MakeSceneWritesEveryNamedScene) {
    for (const std::string& name : named_scene_names()) {
        CommandRun r = run_client("make-scene " + name + " -o " + path("scene.gltf"), dir_);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_THAT(r.output, HasSubstr("scene GUID"));
        Result<Scene> scene = load_scene(dir_ / "scene.gltf");
        ASSERT_TRUE(scene.ok()) << scene.error();
        EXPECT_EQ(scene->lights.size(), make_named_scene(name)->lights.size());
    }
}

TEST_F(LightEditCommands, MakeScenesHelpListsEveryName) {
    CommandRun r = run_client("make-scene --help", dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const std::string& name : named_scene_names()) EXPECT_THAT(r.output, HasSubstr(name));
    EXPECT_THAT(r.output, HasSubstr("cornell-emissive"));
    EXPECT_THAT(r.output, HasSubstr("heavy-room"));
}

TEST_F(LightEditCommands, ErrorsNameTheProblem) {
    ASSERT_EQ(run_client("make-scene room -o " + path("room.gltf"), dir_).exit_code, 0);
    struct Case {
        std::string args;
        const char* message;
    };
    const std::vector<Case> cases{
        {"add-lights --count 3 --layout spiral -o " + path("x.gltf"),
         "unknown light layout 'spiral'"},
        {"add-lights --count 3 --layout grid --type area -o " + path("x.gltf"),
         "unknown light type 'area'"},
        {"add-lights --count 0 --layout grid -o " + path("x.gltf"), "at least 1"},
        {"add-lights --count 3 --layout grid --box 1,2,3 -o " + path("x.gltf"), "exactly 6"},
        {"add-lights --count 3 --layout grid --box 0,0,0,1,1,nan -o " + path("x.gltf"),
         "not a finite number"},
        {"add-lights --count 3 --layout grid --intensity -2 -o " + path("x.gltf"), "intensity"},
        {"add-lights " + path("missing.gltf") + " --count 3 --layout grid -o " + path("x.gltf"),
         "file does not exist"},
        {"remove-lights " + path("room.gltf") + " -o " + path("x.gltf"),
         "one of --index, --guid or --all"},
        {"remove-lights " + path("room.gltf") + " --index 0 -o " + path("x.gltf"),
         "the scene has 0 lights"},
        {"remove-lights " + path("room.gltf") + " --guid nope -o " + path("x.gltf"),
         "'nope' is not a GUID"},
        {"make-scene cathedral -o " + path("x.gltf"), "unknown scene 'cathedral'"},
        {"make-scene room -o " + (dir_ / "no" / "dir.gltf").string(), "does not exist"},
    };
    for (const Case& c : cases) {
        CommandRun r = run_client(c.args, dir_);
        EXPECT_NE(r.exit_code, 0) << c.args;
        EXPECT_THAT(r.output, HasSubstr(c.message)) << c.args;
    }
    EXPECT_FALSE(std::filesystem::exists(dir_ / "x.gltf"));
}

}  // namespace
}  // namespace lc::client
