// The environment a glTF names in asset.extras (gltf_environment.h): a map
// resolved like the file's other resources, or a sun and sky; errors naming
// the field; the writer's round trip; the command line overriding the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "editor_client/commands/environment_flags.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "test_paths.h"

namespace lc::client {
namespace {

// A w x h Radiance file whose texels are all 2.0 (RGBE 128, 128, 128, 130).
void write_uniform_hdr(const std::filesystem::path& path, uint32_t w, uint32_t h) {
    std::ofstream out(path, std::ios::binary);
    out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " << h << " +X " << w << "\n";
    for (uint32_t i = 0; i < w * h; ++i) out << char(128) << char(128) << char(128) << char(130);
}

// A glTF with one triangle-free scene and `extras` as the asset's extras.
void write_gltf(const std::filesystem::path& path, const std::string& extras) {
    std::ofstream out(path);
    out << R"({"asset": {"version": "2.0", "extras": )" << extras << R"(}, "scenes": [{"nodes": []}], "scene": 0})";
}

class GltfEnvironment : public ::testing::Test {
protected:
    void SetUp() override { dir_ = test::make_temp_dir("gltf-environment"); }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    Result<Scene> load(const std::string& extras, GltfLoadOptions options = {}) {
        write_gltf(dir_ / "scene.gltf", extras);
        return load_scene(dir_ / "scene.gltf", options);
    }
    // The error of loading `extras`, which must fail.
    std::string error_of(const std::string& extras) {
        Result<Scene> scene = load(extras);
        EXPECT_FALSE(scene) << extras;
        return scene ? std::string() : scene.error();
    }

    std::filesystem::path dir_;
};

TEST_F(GltfEnvironment, MapResolvesBesideTheFileWithItsIntensityAndRotation) {
    write_uniform_hdr(dir_ / "sky.hdr", 8, 4);
    Result<Scene> scene = load(R"({"lightcuts_environment": {"image": "sky.hdr", "intensity": 0.5, "rotation": 30}})");
    ASSERT_TRUE(scene) << scene.error();
    ASSERT_TRUE(scene->environment);
    const Environment& environment = *scene->environment;
    ASSERT_TRUE(environment.has_map());
    EXPECT_EQ(environment.map.width, 8u);
    EXPECT_EQ(environment.map.height, 4u);
    EXPECT_EQ(environment.map.texels[0], glm::vec3(2.0f));
    EXPECT_EQ(environment.intensity, 0.5f);
    EXPECT_EQ(environment.rotation_deg, 30.0f);
    EXPECT_EQ(scene->environment_image, dir_ / "sky.hdr");
}

TEST_F(GltfEnvironment, SkyTakesItsParametersAndDefaultsTheIntensity) {
    Result<Scene> scene = load(R"({"lightcuts_sky": {"elevation": 20, "azimuth": -45.5, "turbidity": 4}})");
    ASSERT_TRUE(scene) << scene.error();
    ASSERT_TRUE(scene->environment && scene->environment->has_sky());
    EXPECT_EQ(*scene->environment->sky, (SkyParameters{20.0f, -45.5f, 4.0f}));
    EXPECT_EQ(scene->environment->intensity, 1.0f);
}

TEST_F(GltfEnvironment, NoExtrasNoEnvironment) {
    Result<Scene> scene = load(R"({"something_else": 1})");
    ASSERT_TRUE(scene) << scene.error();
    EXPECT_FALSE(scene->environment);
}

TEST_F(GltfEnvironment, BadValuesNameTheField) {
    write_uniform_hdr(dir_ / "sky.hdr", 8, 4);
    const std::pair<const char*, const char*> cases[] = {
        {R"({"lightcuts_environment": {"image": "sky.hdr", "intensity": -1}})",
         "asset.extras.lightcuts_environment.intensity is -1"},
        {R"({"lightcuts_environment": {"image": "sky.hdr", "rotation": "north"}})",
         "asset.extras.lightcuts_environment.rotation is not a number"},
        {R"({"lightcuts_environment": {"intensity": 2}})", "asset.extras.lightcuts_environment.image is missing"},
        {R"({"lightcuts_environment": {"image": "nowhere.hdr"}})",
         "asset.extras.lightcuts_environment.image 'nowhere.hdr': "},
        {R"({"lightcuts_environment": "sky.hdr"})", "asset.extras.lightcuts_environment is not an object"},
        {R"({"lightcuts_sky": {"elevation": 20, "turbidity": 4}})", "asset.extras.lightcuts_sky.azimuth is missing"},
        {R"({"lightcuts_sky": {"elevation": 20, "azimuth": 0, "turbidity": 40}})",
         "asset.extras.lightcuts_sky: sky: turbidity 40"},
        {R"({"lightcuts_sky": {"elevation": 20, "azimuth": 0, "turbidity": 4, "intensity": -2}})",
         "asset.extras.lightcuts_sky.intensity is -2"},
        {R"({"lightcuts_sky": {"elevation": 20, "azimuth": 0, "turbidity": 4},
             "lightcuts_environment": {"image": "sky.hdr"}})",
         "names both lightcuts_environment and lightcuts_sky"},
    };
    for (const auto& [extras, expected] : cases) {
        const std::string error = error_of(extras);
        EXPECT_NE(error.find(expected), std::string::npos) << extras << "\n" << error;
        EXPECT_EQ(error.rfind((dir_ / "scene.gltf").string() + ": ", 0), 0u) << error;
    }
    // A file that is not HDR is refused as the image it is.
    std::ofstream(dir_ / "not.hdr") << "plain text";
    EXPECT_NE(error_of(R"({"lightcuts_environment": {"image": "not.hdr"}})").find("not a Radiance HDR file"),
              std::string::npos);
}

TEST_F(GltfEnvironment, AnImageOutsideTheFolderNeedsAllowExternalResources) {
    const std::filesystem::path outside = test::make_temp_dir("gltf-environment-outside");
    write_uniform_hdr(outside / "far.hdr", 8, 4);
    const std::string extras =
        R"({"lightcuts_environment": {"image": ")" + (outside / "far.hdr").string() + R"("}})";
    const std::string error = error_of(extras);
    EXPECT_NE(error.find("lies outside the scene's folder"), std::string::npos) << error;
    GltfLoadOptions external;
    external.allow_external_resources = true;
    Result<Scene> scene = load(extras, external);
    ASSERT_TRUE(scene) << scene.error();
    EXPECT_TRUE(scene->environment && scene->environment->has_map());
    std::filesystem::remove_all(outside);
}

TEST_F(GltfEnvironment, WriterRoundTripsTheMapAndTheSky) {
    write_uniform_hdr(dir_ / "sky.hdr", 8, 4);
    Result<Scene> with_map =
        load(R"({"lightcuts_environment": {"image": "sky.hdr", "intensity": 0.25, "rotation": -90}})");
    ASSERT_TRUE(with_map) << with_map.error();
    ASSERT_TRUE(write_scene_gltf(*with_map, dir_ / "written.gltf"));
    Result<Scene> again = load_scene(dir_ / "written.gltf");
    ASSERT_TRUE(again) << again.error();
    ASSERT_TRUE(again->environment && again->environment->has_map());
    EXPECT_EQ(again->environment->intensity, 0.25f);
    EXPECT_EQ(again->environment->rotation_deg, -90.0f);
    EXPECT_EQ(again->environment_image, dir_ / "sky.hdr");

    // Lights written into a copy in a subfolder: the image's path follows.
    std::filesystem::create_directories(dir_ / "sub");
    ASSERT_TRUE(write_lights_into_gltf(dir_ / "scene.gltf", {}, dir_ / "sub" / "copy.gltf"));
    Result<Scene> copy = load_scene(dir_ / "sub" / "copy.gltf", GltfLoadOptions{.allow_external_resources = true});
    ASSERT_TRUE(copy) << copy.error();
    ASSERT_TRUE(copy->environment && copy->environment->has_map());
    EXPECT_EQ(std::filesystem::canonical(copy->environment_image), std::filesystem::canonical(dir_ / "sky.hdr"));

    Scene with_sky;
    auto sky = std::make_shared<Environment>();
    sky->sky = SkyParameters{12.5f, 200.0f, 2.5f};
    sky->intensity = 3.0f;
    with_sky.environment = sky;
    ASSERT_TRUE(write_scene_gltf(with_sky, dir_ / "sky.gltf"));
    Result<Scene> sky_again = load_scene(dir_ / "sky.gltf");
    ASSERT_TRUE(sky_again) << sky_again.error();
    ASSERT_TRUE(sky_again->environment && sky_again->environment->has_sky());
    EXPECT_EQ(*sky_again->environment->sky, *sky->sky);
    EXPECT_EQ(sky_again->environment->intensity, 3.0f);

    // A scene without one writes none.
    ASSERT_TRUE(write_scene_gltf(Scene{}, dir_ / "none.gltf"));
    std::ifstream none(dir_ / "none.gltf");
    const std::string text((std::istreambuf_iterator<char>(none)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("extras"), std::string::npos) << text;
}

TEST_F(GltfEnvironment, CommandLineFlagsOverrideTheFile) {
    Result<Scene> scene = load(R"({"lightcuts_sky": {"elevation": 20, "azimuth": 0, "turbidity": 4}})");
    ASSERT_TRUE(scene) << scene.error();
    EnvironmentFlags none;
    auto kept = none.load(scene->environment);
    ASSERT_TRUE(kept) << kept.error();
    EXPECT_EQ(kept->get(), scene->environment.get());

    EnvironmentFlags flags;
    flags.sky = "60,90,2";
    auto replaced = flags.load(scene->environment);
    ASSERT_TRUE(replaced) << replaced.error();
    ASSERT_TRUE(*replaced && (*replaced)->has_sky());
    EXPECT_EQ((*replaced)->sky->elevation_deg, 60.0f);

    EnvironmentFlags count_only;
    count_only.lights = 100;
    EXPECT_TRUE(count_only.load(scene->environment));
    EXPECT_FALSE(count_only.load(nullptr));
}

}  // namespace
}  // namespace lc::client
