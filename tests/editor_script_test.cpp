// The editor's command language (--script FILE): parsing with line-numbered
// errors, and the runner executing commands through EditorSession.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "editor_client/editor/editor_command.h"
#include "editor_client/editor/script_runner.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/scene_generator.h"
#include "test_paths.h"

namespace lc::client {
namespace {

// The window side, recording what it was asked to do (screenshots need Vulkan;
// the view tests cover them).
class RecordingHost final : public EditorHost {
public:
    Status screenshot(const std::filesystem::path& path) override {
        screenshots.push_back(path);
        return Ok{};
    }
    void request_quit() override { quit = true; }

    std::vector<std::filesystem::path> screenshots;
    bool quit = false;
};

template <typename T>
T parse_one(std::string_view line) {
    auto command = parse_editor_command(line);
    EXPECT_TRUE(command.ok()) << line << ": " << (command.ok() ? "" : command.error());
    EXPECT_TRUE(command.value().has_value()) << line;
    EXPECT_TRUE(std::holds_alternative<T>(*command.value())) << line;
    return std::get<T>(*command.value());
}

std::string parse_error(std::string_view line) {
    auto command = parse_editor_command(line);
    EXPECT_FALSE(command.ok()) << line;
    return command.ok() ? "" : command.error();
}

TEST(EditorScript, ParsesEveryCommandWithItsValues) {
    cmd::AddLight point = parse_one<cmd::AddLight>("add-light point 1 2.5 -3 1 0.5 0 40 7.5");
    EXPECT_EQ(point.light.type, LightType::kPoint);
    EXPECT_EQ(point.light.position, glm::vec3(1, 2.5f, -3));
    EXPECT_EQ(point.light.color, glm::vec3(1, 0.5f, 0));
    EXPECT_FLOAT_EQ(point.light.intensity, 40.0f);
    EXPECT_FLOAT_EQ(point.light.range, 7.5f);
    EXPECT_FALSE(point.light.classic);
    EXPECT_TRUE(point.light.guid.is_zero());

    cmd::AddLight spot = parse_one<cmd::AddLight>("  add-light spot 0 3 0 1 1 1 100 classic ");
    EXPECT_EQ(spot.light.type, LightType::kSpot);
    EXPECT_FLOAT_EQ(spot.light.range, 0.0f);
    EXPECT_TRUE(spot.light.classic);
    EXPECT_EQ(spot.light.direction, glm::vec3(0, -1, 0));
    EXPECT_LT(spot.light.inner_cone_angle, spot.light.outer_cone_angle);

    cmd::AddLights many = parse_one<cmd::AddLights>("add-lights 4096 grid 3 spot 5 2");
    EXPECT_EQ(many.count, 4096u);
    EXPECT_EQ(many.layout, LightLayout::kGrid);
    EXPECT_EQ(many.seed, 3u);
    EXPECT_EQ(many.type, LightTypeChoice::kSpot);
    EXPECT_EQ(many.intensity, std::optional<float>(5.0f));
    EXPECT_FLOAT_EQ(many.range, 2.0f);

    EXPECT_EQ(parse_one<cmd::RemoveLight>("remove-light 12").index, 12u);
    cmd::MoveLight move = parse_one<cmd::MoveLight>("move-light 2 1 2 3");
    EXPECT_EQ(move.index, 2u);
    EXPECT_EQ(move.position, glm::vec3(1, 2, 3));
    EXPECT_EQ(parse_one<cmd::Mode>("mode cutsize").name, "cutsize");
    EXPECT_EQ(parse_one<cmd::Criterion>("criterion bound").name, "bound");
    EXPECT_DOUBLE_EQ(parse_one<cmd::ErrorRatio>("error-ratio 0.05").ratio, 0.05f);
    EXPECT_EQ(parse_one<cmd::MaxCut>("max-cut 200").max_cut, 200u);
    EXPECT_EQ(parse_one<cmd::RepresentativesChoice>("representatives importance").name, "importance");
    EXPECT_FALSE(parse_editor_command("representatives").ok()) << "the name is required";
    cmd::Camera camera = parse_one<cmd::Camera>("camera 0 1.5 4.5 0 1 0 60  # front");
    EXPECT_EQ(camera.camera.eye, glm::vec3(0, 1.5f, 4.5f));
    EXPECT_EQ(camera.camera.target, glm::vec3(0, 1, 0));
    EXPECT_NEAR(camera.camera.yfov, 60.0 * std::numbers::pi / 180.0, 1e-6);
    EXPECT_EQ(parse_one<cmd::Screenshot>("screenshot out/a b.png").path.string(), "out/a b.png");
    EXPECT_EQ(parse_one<cmd::Save>("save /tmp/x.gltf").path.string(), "/tmp/x.gltf");
    parse_one<cmd::Bake>("bake");
    parse_one<cmd::Quit>("quit");
    parse_one<cmd::Undo>("undo");
}

TEST(EditorScript, BlankAndCommentLinesAreSkipped) {
    for (const char* line : {"", "   ", "# a comment", "\t# indented comment", "\r"}) {
        auto command = parse_editor_command(line);
        ASSERT_TRUE(command.ok()) << command.error();
        EXPECT_FALSE(command.value().has_value()) << "'" << line << "'";
    }
}

TEST(EditorScript, BadLinesNameTheProblem) {
    EXPECT_NE(parse_error("explode now").find("unknown command 'explode'"), std::string::npos);
    EXPECT_NE(parse_error("add-light point 1 2 3").find("takes 8 to 10 arguments"),
              std::string::npos);
    EXPECT_NE(parse_error("add-light laser 0 0 0 1 1 1 1").find("unknown light type 'laser'"),
              std::string::npos);
    EXPECT_NE(parse_error("add-light point 0 nan 0 1 1 1 1").find("position y"), std::string::npos);
    EXPECT_NE(parse_error("add-light point 0 1 0 1 1 1 inf").find("intensity"), std::string::npos);
    EXPECT_NE(parse_error("add-light point 0 1 0 1 1 1 5 3 sparkly").find("sparkly"),
              std::string::npos);
    EXPECT_NE(parse_error("remove-light -1").find("index '-1'"), std::string::npos);
    EXPECT_NE(parse_error("remove-light").find("takes 1 arguments"), std::string::npos);
    EXPECT_NE(parse_error("camera 0 0 1 0 0 0 180").find("fovy"), std::string::npos);
    EXPECT_NE(parse_error("add-lights 0 grid 1").find("count"), std::string::npos);
    EXPECT_NE(parse_error("add-lights 5 spiral 1").find("spiral"), std::string::npos);
    EXPECT_NE(parse_error("save  ").find("PATH"), std::string::npos);
    EXPECT_NE(parse_error("bake now").find("takes 0 arguments"), std::string::npos);
}

TEST(EditorScript, ScriptErrorsNameTheLine) {
    auto script =
        parse_editor_script("# setup\nmode lightcuts\n\nadd-light point 1 2\nbake\n", "edit.txt");
    ASSERT_FALSE(script.ok());
    EXPECT_EQ(script.error().rfind("edit.txt:4: ", 0), 0u) << script.error();

    auto good = parse_editor_script("mode lightcuts\n# c\n\nbake\nquit");
    ASSERT_TRUE(good.ok()) << good.error();
    ASSERT_EQ(good->size(), 3u);
    EXPECT_EQ((*good)[0].line, 1u);
    EXPECT_EQ((*good)[1].line, 4u);
    EXPECT_EQ((*good)[2].line, 5u);

    EXPECT_FALSE(load_editor_script("/nonexistent/script.txt").ok());
}

TEST(EditorScript, RunnerExecutesThroughTheSession) {
    const auto dir = test::make_temp_dir("editor_script");
    auto script = parse_editor_script(
        "add-light point 0 2 0 1 0 0 30 8\n"
        "add-light directional 0 0 0 1 1 1 2\n"
        "add-lights 10 random 5\n"
        "remove-light 1\n"
        "move-light 0 1 2.5 1\n"
        "undo\n"
        "mode cuts\n"
        "criterion bound\n"
        "error-ratio 0.1\n"
        "max-cut 50\n"
        "camera 0 1.5 4 0 1 0 50\n"
        "screenshot " +
        (dir / "shot.png").string() +
        "\n"
        "save " +
        (dir / "saved.gltf").string() +
        "\n"
        "quit\n"
        "remove-light 0\n");
    ASSERT_TRUE(script.ok()) << script.error();
    EditorSession session(make_room_scene());
    RecordingHost host;
    ScriptRunner runner(std::move(script.value()), "run.txt");
    EXPECT_EQ(run_script_to_end(runner, session, host), ScriptState::kQuit) << runner.error();
    EXPECT_TRUE(host.quit);
    EXPECT_EQ(runner.commands_run(), 14u);  // the line after quit did not run

    ASSERT_EQ(session.scene().lights.size(), 11u);
    EXPECT_EQ(session.scene().lights[0].position, glm::vec3(0, 2, 0));  // move undone
    EXPECT_EQ(session.view().mode, RenderMode::kCuts);
    EXPECT_EQ(session.view().criterion, CutCriterion::kBound);
    EXPECT_DOUBLE_EQ(session.view().error_ratio, 0.1f);
    EXPECT_EQ(session.view().max_cut, 50u);
    EXPECT_EQ(session.view().camera.eye, glm::vec3(0, 1.5f, 4));
    ASSERT_EQ(host.screenshots.size(), 1u);
    EXPECT_EQ(host.screenshots[0], dir / "shot.png");

    Result<Scene> saved = load_scene(dir / "saved.gltf");
    ASSERT_TRUE(saved.ok()) << saved.error();
    ASSERT_EQ(saved->lights.size(), 11u);
    EXPECT_FLOAT_EQ(saved->lights[0].intensity, 30.0f);
    EXPECT_FLOAT_EQ(saved->lights[0].range, 8.0f);
    EXPECT_EQ(saved->lights[0].color, glm::vec3(1, 0, 0));
}

TEST(EditorScript, RunnerStopsAtTheFailingLineAndNamesIt) {
    auto script = parse_editor_script("add-light point 0 2 0 1 1 1 5\nremove-light 3\nquit\n");
    ASSERT_TRUE(script.ok()) << script.error();
    EditorSession session(make_room_scene());
    RecordingHost host;
    ScriptRunner runner(std::move(script.value()), "fail.txt");
    EXPECT_EQ(run_script_to_end(runner, session, host), ScriptState::kFailed);
    EXPECT_EQ(runner.error().rfind("fail.txt:2: ", 0), 0u) << runner.error();
    EXPECT_NE(runner.error().find("light 3"), std::string::npos) << runner.error();
    EXPECT_FALSE(host.quit);
    EXPECT_EQ(session.scene().lights.size(), 1u);

    // A bake without a configured server fails on its line too.
    auto bake = parse_editor_script("\nbake\n");
    ASSERT_TRUE(bake.ok());
    ScriptRunner bake_runner(std::move(bake.value()), "bake.txt");
    EXPECT_EQ(run_script_to_end(bake_runner, session, host), ScriptState::kFailed);
    EXPECT_EQ(bake_runner.error().rfind("bake.txt:2: ", 0), 0u) << bake_runner.error();
}

}  // namespace
}  // namespace lc::client
