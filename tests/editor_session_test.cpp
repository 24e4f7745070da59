// EditorSession without a window or server: light edits with validation,
// selection, undo/redo, procedural lights, view controls and saving to glTF.
#include "editor_client/editor/editor_session.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <set>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "test_paths.h"

namespace lc::client {
namespace {

SceneLight point_at(float x, float y, float z, float intensity = 10.0f) {
    SceneLight light;
    light.type = LightType::kPoint;
    light.position = {x, y, z};
    light.color = {1.0f, 0.5f, 0.25f};
    light.intensity = intensity;
    light.range = 6.0f;
    return light;
}

TEST(EditorSession, AddLightAssignsUniqueGuidsSelectsAndBumpsRevision) {
    EditorSession session(make_room_scene());
    ASSERT_TRUE(session.scene().lights.empty());
    const Guid empty_guid = session.scene().guid;
    std::set<Guid> guids;
    for (int i = 0; i < 20; ++i) {
        Result<size_t> index = session.edits().add_light(point_at(float(i) * 0.1f, 1.5f, 0.0f));
        ASSERT_TRUE(index.ok()) << index.error();
        EXPECT_EQ(index.value(), size_t(i));
        EXPECT_EQ(session.edits().selection(), std::optional<size_t>(i));
        guids.insert(session.scene().lights.back().guid);
    }
    EXPECT_EQ(guids.size(), 20u);
    EXPECT_FALSE(guids.contains(Guid{}));
    EXPECT_EQ(session.scene_revision(), 20u);
    EXPECT_NE(session.scene().guid, empty_guid);
    EXPECT_FLOAT_EQ(session.scene().lights[3].position.x, 0.3f);
    EXPECT_FLOAT_EQ(session.scene().lights[3].color.y, 0.5f);

    // Same edits in a second session: the same GUIDs (deterministic).
    EditorSession again(make_room_scene());
    for (int i = 0; i < 20; ++i)
        ASSERT_TRUE(again.edits().add_light(point_at(float(i) * 0.1f, 1.5f, 0.0f)));
    EXPECT_EQ(again.scene().guid, session.scene().guid);
}

TEST(EditorSession, InvalidLightsAreRefusedAndTheSceneIsUnchanged) {
    EditorSession session(make_room_scene());
    ASSERT_TRUE(session.edits().add_light(point_at(0, 1, 0)));
    const uint64_t revision = session.scene_revision();

    SceneLight nan_light = point_at(std::numeric_limits<float>::quiet_NaN(), 1, 0);
    Result<size_t> added = session.edits().add_light(nan_light);
    ASSERT_FALSE(added.ok());
    EXPECT_NE(added.error().find("position"), std::string::npos) << added.error();

    SceneLight negative = point_at(0, 1, 0, -3.0f);
    added = session.edits().add_light(negative);
    ASSERT_FALSE(added.ok());
    EXPECT_NE(added.error().find("intensity"), std::string::npos) << added.error();

    SceneLight bad_range = point_at(0, 1, 0);
    bad_range.range = -1.0f;
    EXPECT_FALSE(session.edits().add_light(bad_range).ok());

    SceneLight bad_spot = point_at(0, 1, 0);
    bad_spot.type = LightType::kSpot;
    bad_spot.direction = {0, -1, 0};
    bad_spot.inner_cone_angle = 1.0f;
    bad_spot.outer_cone_angle = 0.5f;  // inner >= outer
    EXPECT_FALSE(session.edits().add_light(bad_spot).ok());

    EXPECT_EQ(session.scene().lights.size(), 1u);
    EXPECT_EQ(session.scene_revision(), revision);
    EXPECT_EQ(session.edits().undo_stack().undo_depth(), 1u);
}

TEST(EditorSession, RemoveMoveUpdateAndSelectionFollowsItsLight) {
    EditorSession session(make_room_scene());
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(session.edits().add_light(point_at(float(i), 1, 0)));
    const Guid third = session.scene().lights[3].guid;
    ASSERT_TRUE(session.edits().select(3));
    ASSERT_TRUE(session.edits().remove_light(1));
    ASSERT_EQ(session.scene().lights.size(), 3u);
    EXPECT_EQ(session.edits().selection(), std::optional<size_t>(2));
    EXPECT_EQ(session.scene().lights[2].guid, third);
    ASSERT_TRUE(session.edits().remove_light(2));
    EXPECT_FALSE(session.edits().selection().has_value());

    Status out_of_range = session.edits().remove_light(7);
    ASSERT_FALSE(out_of_range.ok());
    EXPECT_NE(out_of_range.error().find("light 7"), std::string::npos) << out_of_range.error();
    EXPECT_NE(out_of_range.error().find("2 lights"), std::string::npos) << out_of_range.error();
    EXPECT_FALSE(session.edits().select(5).ok());

    ASSERT_TRUE(session.edits().move_light(0, {2.0f, 2.5f, -1.0f}));
    EXPECT_EQ(session.scene().lights[0].position, glm::vec3(2.0f, 2.5f, -1.0f));
    EXPECT_FALSE(session.edits().move_light(0, {INFINITY, 0, 0}).ok());
    EXPECT_EQ(session.scene().lights[0].position, glm::vec3(2.0f, 2.5f, -1.0f));

    const Guid guid0 = session.scene().lights[0].guid;
    SceneLight changed = session.scene().lights[0];
    changed.guid = Guid{9, 9, 9, 9};  // ignored: a light keeps its GUID
    changed.color = {0.0f, 1.0f, 0.0f};
    changed.intensity = 42.0f;
    changed.classic = true;
    ASSERT_TRUE(session.edits().update_light(0, changed));
    EXPECT_EQ(session.scene().lights[0].guid, guid0);
    EXPECT_FLOAT_EQ(session.scene().lights[0].intensity, 42.0f);
    EXPECT_TRUE(session.scene().lights[0].classic);
    // The scene bounds follow the lights.
    EXPECT_GE(session.scene().bounds_max.y, 2.5f);
}

TEST(EditorSession, UndoAndRedoRestoreLightsAndSelection) {
    EditorSession session(make_room_scene());
    EXPECT_FALSE(session.edits().undo().ok());
    ASSERT_TRUE(session.edits().add_light(point_at(0, 1, 0)));
    ASSERT_TRUE(session.edits().add_light(point_at(1, 1, 0)));
    const Guid scene_with_two = session.scene().guid;
    ASSERT_TRUE(session.edits().move_light(1, {3, 2, 1}));
    ASSERT_TRUE(session.edits().remove_light(0));
    ASSERT_EQ(session.scene().lights.size(), 1u);
    EXPECT_EQ(session.edits().undo_stack().next_undo_label(), "remove light 0");

    ASSERT_TRUE(session.edits().undo());  // the removal
    ASSERT_EQ(session.scene().lights.size(), 2u);
    EXPECT_EQ(session.scene().lights[1].position, glm::vec3(3, 2, 1));
    ASSERT_TRUE(session.edits().undo());  // the move
    EXPECT_EQ(session.scene().lights[1].position, glm::vec3(1, 1, 0));
    EXPECT_EQ(session.scene().guid, scene_with_two);
    ASSERT_TRUE(session.edits().redo());
    EXPECT_EQ(session.scene().lights[1].position, glm::vec3(3, 2, 1));
    ASSERT_TRUE(session.edits().undo());
    ASSERT_TRUE(session.edits().undo());
    ASSERT_TRUE(session.edits().undo());
    EXPECT_TRUE(session.scene().lights.empty());
    EXPECT_FALSE(session.edits().selection().has_value());
    EXPECT_FALSE(session.edits().undo().ok());
    // A new edit clears the redo side.
    ASSERT_TRUE(session.edits().add_light(point_at(0, 2, 0)));
    EXPECT_FALSE(session.edits().redo().ok());
}

TEST(EditorSession, UndoStackKeepsTheLastEditWithinItsBudget) {
    UndoStack stack(/*max_entries=*/3, /*max_total_lights=*/10);
    for (int i = 0; i < 5; ++i)
        stack.push(EditSnapshot{"edit " + std::to_string(i), std::vector<SceneLight>(4), {}});
    // 3 entries of 4 lights exceed the 10-light budget: 2 stay.
    EXPECT_EQ(stack.undo_depth(), 2u);
    EXPECT_EQ(stack.next_undo_label(), "edit 4");
    stack.push(EditSnapshot{"huge", std::vector<SceneLight>(100), {}});
    EXPECT_EQ(stack.undo_depth(), 1u);  // the last edit is always undoable
    EXPECT_EQ(stack.next_undo_label(), "huge");
}

TEST(EditorSession, ProceduralLightsAreDeterministicInsideTheBoxAndOneUndoStep) {
    EditorSession a(make_room_scene());
    EditorSession b(make_room_scene());
    LightLayoutOptions layout;
    layout.count = 64;
    layout.seed = 7;
    layout.box_min = kRoomLightBoxMin;
    layout.box_max = kRoomLightBoxMax;
    ASSERT_EQ(a.edits().add_procedural_lights(layout).value(), 64u);
    ASSERT_EQ(b.edits().add_procedural_lights(layout).value(), 64u);
    ASSERT_EQ(a.scene().lights.size(), 64u);
    for (size_t i = 0; i < 64; ++i) {
        const SceneLight& light = a.scene().lights[i];
        EXPECT_EQ(light.guid, b.scene().lights[i].guid);
        EXPECT_EQ(light.position, b.scene().lights[i].position);
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(light.position[k], kRoomLightBoxMin[k]);
            EXPECT_LE(light.position[k], kRoomLightBoxMax[k]);
        }
    }
    // The same seed again adds 64 distinct lights.
    ASSERT_TRUE(a.edits().add_procedural_lights(layout));
    std::set<Guid> guids;
    for (const SceneLight& light : a.scene().lights) guids.insert(light.guid);
    EXPECT_EQ(guids.size(), 128u);
    ASSERT_TRUE(a.edits().undo());
    EXPECT_EQ(a.scene().lights.size(), 64u);

    layout.count = 0;
    Result<size_t> none = a.edits().add_procedural_lights(layout);
    ASSERT_FALSE(none.ok());
    EXPECT_NE(none.error().find("count"), std::string::npos) << none.error();
}

TEST(EditorSession, ViewControlsValidate) {
    EditorSession session(make_room_scene());
    EXPECT_EQ(session.view().criterion, CutCriterion::kBound) << "the paper's criterion by default";
    ASSERT_TRUE(session.view_settings().set_mode("lightcuts"));
    EXPECT_EQ(session.view().mode, RenderMode::kLightcuts);
    Status bad_mode = session.view_settings().set_mode("sparkles");
    ASSERT_FALSE(bad_mode.ok());
    EXPECT_NE(bad_mode.error().find("sparkles"), std::string::npos);
    EXPECT_NE(bad_mode.error().find("reference"), std::string::npos) << bad_mode.error();
    EXPECT_EQ(session.view().mode, RenderMode::kLightcuts);

    ASSERT_TRUE(session.view_settings().set_criterion("bound"));
    EXPECT_EQ(session.view().criterion, CutCriterion::kBound);
    EXPECT_FALSE(session.view_settings().set_criterion("vibes").ok());

    ASSERT_TRUE(session.view_settings().set_error_ratio(0.05));
    EXPECT_DOUBLE_EQ(session.view().cut_settings().error_ratio, 0.05);
    EXPECT_FALSE(session.view_settings().set_error_ratio(0.0).ok());
    EXPECT_FALSE(session.view_settings().set_error_ratio(std::nan("")).ok());
    EXPECT_FALSE(session.view_settings().set_error_ratio(2.0).ok());
    EXPECT_DOUBLE_EQ(session.view().error_ratio, 0.05);

    ASSERT_TRUE(session.view_settings().set_max_cut(64));
    EXPECT_EQ(session.view().max_cut, 64u);
    EXPECT_FALSE(session.view_settings().set_max_cut(0).ok());
    EXPECT_FALSE(session.view_settings().set_max_cut(kMaxGpuCut + 1).ok()) << "the renderer would refuse it";

    EXPECT_EQ(session.view().representatives, Representatives::kTree) << "as render defaults to";
    ASSERT_TRUE(session.view_settings().set_representatives("importance"));
    EXPECT_EQ(session.view().representatives, Representatives::kImportance);
    Status bad_draw = session.view_settings().set_representatives("lottery");
    ASSERT_FALSE(bad_draw.ok());
    EXPECT_NE(bad_draw.error().find("importance"), std::string::npos) << bad_draw.error();
    // Per-pixel draws need the bound criterion: the switch is refused, the view unchanged.
    Status radius = session.view_settings().set_criterion("radius");
    ASSERT_FALSE(radius.ok());
    EXPECT_NE(radius.error().find("bound criterion"), std::string::npos) << radius.error();
    EXPECT_EQ(session.view().criterion, CutCriterion::kBound);

    // Every control reaches the renderer (error ratio and max cut once did not).
    RenderSettings shown = render_settings_for(session.view(), 320, 200, /*has_tree=*/true);
    EXPECT_EQ(shown.mode, RenderMode::kLightcuts);
    EXPECT_EQ(shown.criterion, CutCriterion::kBound);
    EXPECT_FLOAT_EQ(shown.error_ratio, 0.05f);
    EXPECT_EQ(shown.max_cut, 64u);
    EXPECT_EQ(shown.representatives, Representatives::kImportance);
    EXPECT_EQ(shown.width, 320u);
    EXPECT_EQ(shown.height, 200u);
    EXPECT_EQ(render_settings_for(session.view(), 320, 200, false).mode, RenderMode::kReference);

    RenderCamera camera;
    camera.eye = {0, 1, 4};
    camera.target = {0, 1, 0};
    ASSERT_TRUE(session.view_settings().set_camera(camera));
    camera.target = camera.eye;
    EXPECT_FALSE(session.view_settings().set_camera(camera).ok());
    camera.target = {0, 0, 0};
    camera.yfov = 0.0f;
    EXPECT_FALSE(session.view_settings().set_camera(camera).ok());
    EXPECT_EQ(session.view().camera.eye, glm::vec3(0, 1, 4));
    EXPECT_FALSE(session.view_settings().set_exposure(-1.0f).ok());
}

TEST(EditorSession, BakeWithoutServerSaysHowToConfigureOne) {
    EditorSession session(make_room_scene());
    Status bake = session.start_bake();
    ASSERT_FALSE(bake.ok());
    EXPECT_NE(bake.error().find("--server"), std::string::npos) << bake.error();
    EXPECT_FALSE(session.baking().bake_running());
    EXPECT_FALSE(session.tree_matches_scene());
    EXPECT_NE(session.baking().server_description().find("none"), std::string::npos);
}

TEST(EditorSession, SaveGeneratedSceneWritesLightsBack) {
    const auto dir = test::make_temp_dir("editor_save");
    EditorSession session(make_room_scene());
    SceneLight spot = point_at(1, 2.5f, -1, 25.0f);
    spot.type = LightType::kSpot;
    spot.direction = {0, -1, 0};
    spot.inner_cone_angle = 0.2f;
    spot.outer_cone_angle = 0.6f;
    ASSERT_TRUE(session.edits().add_light(point_at(-2, 1.5f, 0.5f, 12.0f)));
    ASSERT_TRUE(session.edits().add_light(spot));
    ASSERT_TRUE(session.edits().save(dir / "saved.gltf"));

    Result<Scene> loaded = load_scene(dir / "saved.gltf");
    ASSERT_TRUE(loaded.ok()) << loaded.error();
    ASSERT_EQ(loaded->lights.size(), 2u);
    EXPECT_FALSE(loaded->meshes.empty());
    for (size_t i = 0; i < 2; ++i) {
        const SceneLight& want = session.scene().lights[i];
        const SceneLight& got = loaded->lights[i];
        EXPECT_EQ(got.guid, want.guid);
        EXPECT_EQ(got.type, want.type);
        EXPECT_NEAR(glm::length(got.position - want.position), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::length(got.color - want.color), 0.0f, 1e-6f);
        EXPECT_FLOAT_EQ(got.intensity, want.intensity);
        EXPECT_FLOAT_EQ(got.range, want.range);
    }
    EXPECT_NEAR(loaded->lights[1].direction.y, -1.0f, 1e-5f);
    EXPECT_NEAR(loaded->lights[1].outer_cone_angle, 0.6f, 1e-6f);
    EXPECT_FALSE(session.edits().save("").ok());
}

TEST(EditorSession, SaveLoadedFileKeepsItsGeometryAndReplacesLights) {
    const auto dir = test::make_temp_dir("editor_save_loaded");
    Scene room = make_room_scene();
    SceneLight first = point_at(0, 2, 0);
    first.guid = Guid{1, 2, 3, 4};
    room.lights.push_back(first);
    ASSERT_TRUE(write_scene_gltf(room, dir / "room.gltf"));
    Result<Scene> loaded = load_scene(dir / "room.gltf");
    ASSERT_TRUE(loaded.ok()) << loaded.error();
    const size_t meshes = loaded->meshes.size();

    EditorSession session(std::move(loaded.value()));
    ASSERT_TRUE(session.edits().add_light(point_at(3, 1, 3, 5.0f)));
    ASSERT_TRUE(session.edits().remove_light(0));
    ASSERT_TRUE(session.edits().save(dir / "edited.gltf"));
    Result<Scene> edited = load_scene(dir / "edited.gltf");
    ASSERT_TRUE(edited.ok()) << edited.error();
    EXPECT_EQ(edited->meshes.size(), meshes);
    ASSERT_EQ(edited->lights.size(), 1u);
    EXPECT_EQ(edited->lights[0].guid, session.scene().lights[0].guid);
    EXPECT_FLOAT_EQ(edited->lights[0].intensity, 5.0f);
    EXPECT_NEAR(edited->lights[0].position.x, 3.0f, 1e-5f);
}

}  // namespace
}  // namespace lc::client
