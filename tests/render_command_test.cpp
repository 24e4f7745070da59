// `editor_client render` end to end, as a user runs it: a glTF scene written
// by the scene generator, a tree dump written like `bake -o` writes it, every
// mode, then the PNG, the PFM and the stats JSON are read back and checked.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "editor_client/render/output/exr_image.h"
#include "editor_client/render/output/image_io.h"
#include "lightcuts/tone_mapping.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/scene_generator.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/dump.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

struct CommandRun {
    int exit_code = -1;
    std::string output;  // stdout and stderr
};

CommandRun run(const std::string& args, const std::filesystem::path& dir) {
    std::filesystem::path log = dir / "command.log";
    std::string command = (test::bin_dir() / "editor_client").string() + " render " + args + " > " +
                          log.string() + " 2>&1";
    CommandRun r;
    int status = std::system(command.c_str());
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    r.output = text.str();
    return r;
}

class RenderCommand : public ::testing::Test {
protected:
    void SetUp() override {
        std::unique_ptr<vk::Context> probe;
        LC_REQUIRE_VULKAN(probe);
        probe.reset();
        dir_ = test::make_temp_dir("render-command");

        Scene scene = make_room_scene();
        LightLayoutOptions layout;
        layout.count = 24;
        layout.seed = 7;
        layout.type = LightTypeChoice::kMixed;
        layout.box_min = kRoomLightBoxMin;
        layout.box_max = kRoomLightBoxMax;
        layout.range = 6.0f;
        Result<std::vector<SceneLight>> lights = generate_lights(layout);
        ASSERT_TRUE(lights.ok()) << lights.error();
        scene.lights = *lights;
        scene_path_ = dir_ / "room.gltf";
        ASSERT_TRUE(write_scene_gltf(scene, scene_path_).ok());

        Result<bake::BuildResult> built = bake::build_light_tree(scene.lights, {}, nullptr);
        ASSERT_TRUE(built.ok()) << built.error();
        nodes_ = built->tree.nodes.size();
        tree_path_ = dir_ / "room.lcut";
        ASSERT_TRUE(write_dump(tree_path_, ChannelDump{lightcuts_result_channel_name(),
                                                       encode_result_channel(built->tree)})
                        .ok());
    }
    void TearDown() override {
        if (!dir_.empty()) std::filesystem::remove_all(dir_);
    }

    std::filesystem::path dir_, scene_path_, tree_path_;
    size_t nodes_ = 0;
};

TEST_F(RenderCommand, EveryModeWritesImagesAndStats) {
    for (const char* mode : {"reference", "lightcuts", "cuts", "cutsize"}) {
        SCOPED_TRACE(mode);
        std::filesystem::path png = dir_ / (std::string(mode) + ".png");
        std::filesystem::path pfm = dir_ / (std::string(mode) + ".pfm");
        std::filesystem::path stats_path = dir_ / (std::string(mode) + ".json");
        CommandRun r = run(scene_path_.string() + " --tree " + tree_path_.string() + " --mode " +
                               mode + " --size 80x60 --validation -o " + png.string() +
                               " --float " + pfm.string() + " --stats " + stats_path.string(),
                           dir_);
        ASSERT_EQ(r.exit_code, 0) << r.output;

        Result<Rgba8Image> image = read_png(png);
        ASSERT_TRUE(image.ok()) << image.error();
        EXPECT_EQ(image->width, 80u);
        EXPECT_EQ(image->height, 60u);
        size_t lit = 0;
        for (size_t i = 0; i < image->rgba.size(); i += 4)
            lit += (image->rgba[i] + image->rgba[i + 1] + image->rgba[i + 2]) > 30 ? 1 : 0;
        EXPECT_GT(lit, 80u * 60u / 4) << "image is mostly black";

        Result<FloatImage> hdr = read_pfm(pfm);
        ASSERT_TRUE(hdr.ok()) << hdr.error();
        EXPECT_EQ(hdr->width, 80u);
        EXPECT_EQ(hdr->height, 60u);
        for (float v : hdr->rgb) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);

        std::ifstream in(stats_path);
        nlohmann::json stats = nlohmann::json::parse(in);
        for (const char* key :
             {"scene", "lights", "tree_lights", "classic_lights", "nodes", "mode", "criterion",
              "width", "height", "render_ms", "wall_ms", "avg_cut", "max_cut", "nonfinite_pixels",
              "effects_simulated", "effects_skipped", "validation_messages"})
            EXPECT_TRUE(stats.contains(key)) << key;
        EXPECT_EQ(stats["mode"], mode);
        EXPECT_EQ(stats["width"], 80);
        EXPECT_EQ(stats["nodes"], nodes_);
        EXPECT_EQ(stats["tree_lights"], 24);
        EXPECT_EQ(stats["nonfinite_pixels"], 0);
        EXPECT_EQ(stats["validation_messages"], 0);
        EXPECT_GT(stats["render_ms"].get<double>(), 0.0);
        EXPECT_GE(stats["max_cut"].get<int>(), 1);
        // The mixed layout has every light type: those effects are simulated.
        std::string simulated = stats["effects_simulated"].dump();
        EXPECT_NE(simulated.find("spot cone attenuation"), std::string::npos) << simulated;
        EXPECT_NE(simulated.find("range windowing"), std::string::npos) << simulated;
        std::string skipped = stats["effects_skipped"].dump();
        EXPECT_NE(skipped.find("classic lights"), std::string::npos) << skipped;
    }
}

TEST_F(RenderCommand, FloatImageHoldsTheLinearRadianceBottomUp) {
    // Write both images of one frame; the PNG's top row must be the tone map of
    // the PFM's top row (which PFM stores last).
    std::filesystem::path png = dir_ / "ref.png", pfm = dir_ / "ref.pfm";
    CommandRun r = run(scene_path_.string() + " --size 32x24 --exposure 0.5 -o " + png.string() +
                           " --float " + pfm.string(),
                       dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    Result<Rgba8Image> image = read_png(png);
    Result<FloatImage> hdr = read_pfm(pfm);
    ASSERT_TRUE(image.ok() && hdr.ok());
    int max_diff = 0;
    for (size_t i = 0; i < size_t(32) * 24; ++i)
        for (int ch = 0; ch < 3; ++ch)
            max_diff = std::max(max_diff,
                                std::abs(int(image->rgba[4 * i + ch]) -
                                         int(tone::to_display_byte(hdr->rgb[3 * i + ch], 0.5f))));
    EXPECT_LE(max_diff, 1);
    // Raw file layout: the first stored row is the image's bottom row.
    std::ifstream raw(pfm, std::ios::binary);
    std::string header;
    for (int lines = 0; lines < 3; ++lines) std::getline(raw, header);
    float first[3];
    raw.read(reinterpret_cast<char*>(first), sizeof(first));
    const size_t bottom_left = size_t(23) * 32;
    EXPECT_EQ(first[0], hdr->rgb[3 * bottom_left]);
}

TEST_F(RenderCommand, ExrImageIsThePfmBitForBitAndHalfWhenAsked) {
    // -o IMAGE.exr writes the linear frame the PFM holds, to the last bit in float mode.
    std::filesystem::path exr = dir_ / "frame.exr", pfm = dir_ / "frame.pfm", half = dir_ / "half.exr";
    CommandRun r = run(scene_path_.string() + " --tree " + tree_path_.string() + " --size 40x30 -o " +
                           exr.string() + " --float " + pfm.string(),
                       dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    Result<FloatImage> from_exr = read_exr(exr);
    Result<FloatImage> from_pfm = read_pfm(pfm);
    ASSERT_TRUE(from_exr.ok()) << from_exr.error();
    ASSERT_TRUE(from_pfm.ok()) << from_pfm.error();
    ASSERT_EQ(from_exr->width, 40u);
    ASSERT_EQ(from_exr->height, 30u);
    ASSERT_EQ(from_exr->rgb.size(), from_pfm->rgb.size());
    EXPECT_EQ(std::memcmp(from_exr->rgb.data(), from_pfm->rgb.data(), from_pfm->rgb.size() * sizeof(float)), 0);
    float brightest = 0.0f;
    for (float v : from_pfm->rgb) brightest = std::max(brightest, v);
    EXPECT_GT(brightest, 0.0f) << "the frame is black";
    Result<std::string> mode = read_exr_attribute(exr, "lightcuts.mode");
    ASSERT_TRUE(mode.ok()) << mode.error();
    EXPECT_EQ(*mode, "lightcuts");
    if (std::system("command -v exrheader > /dev/null 2>&1") == 0) {
        const std::string command = "exrheader " + exr.string() + " > " + (dir_ / "header.txt").string() + " 2>&1";
        EXPECT_EQ(std::system(command.c_str()), 0) << test::read_text(dir_ / "header.txt");
    }

    r = run(scene_path_.string() + " --tree " + tree_path_.string() + " --size 40x30 --exr-half -o " + half.string(),
            dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    Result<FloatImage> from_half = read_exr(half);
    ASSERT_TRUE(from_half.ok()) << from_half.error();
    ASSERT_EQ(from_half->rgb.size(), from_pfm->rgb.size());
    for (size_t i = 0; i < from_pfm->rgb.size(); ++i) {
        const float v = from_pfm->rgb[i];
        // Half keeps 11 significant bits: the nearest half is within half an ulp (2^-11 relative).
        ASSERT_NEAR(from_half->rgb[i], v, std::max(std::abs(v) * 0x1p-11f, 0x1p-24f)) << "value " << i;
    }

    r = run(scene_path_.string() + " --size 8x8 --exr-half -o " + (dir_ / "x.png").string(), dir_);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("--exr-half needs an .exr image"), std::string::npos) << r.output;
}

TEST_F(RenderCommand, BakesOnASpawnedServer) {
    // The whole path: scene -> lightmass_server -> result channel -> GPU cut.
    std::filesystem::path png = dir_ / "spawned.png", stats_path = dir_ / "spawned.json";
    CommandRun r =
        run(scene_path_.string() + " --spawn-server --builder agglomerative --mode cutsize" +
                " --size 48x36 -o " + png.string() + " --stats " + stats_path.string(),
            dir_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::ifstream in(stats_path);
    nlohmann::json stats = nlohmann::json::parse(in);
    EXPECT_EQ(stats["tree_lights"], 24);
    EXPECT_EQ(stats["nodes"], 2 * 24 - 1);  // a binary tree over 24 leaves
    EXPECT_GE(stats["max_cut"].get<int>(), 1);
    EXPECT_EQ(stats["nonfinite_pixels"], 0);
    EXPECT_TRUE(std::filesystem::exists(png));
}

TEST_F(RenderCommand, SupersamplingIsDeterministicAndCountsItsWork) {
    // --spp with reconstruction cuts, twice with the same seed: the same bytes;
    // another seed moves the eye rays; the stats say what was computed.
    auto render_spp = [&](const std::string& tag, const std::string& seed) {
        std::filesystem::path pfm = dir_ / (tag + ".pfm"), stats = dir_ / (tag + ".json");
        CommandRun r = run(scene_path_.string() + " --tree " + tree_path_.string() +
                               " --size 32x24 --spp 4 --spp-method reconstruction --spp-seed " +
                               seed + " --compare-reference -o " + (dir_ / (tag + ".png")).string() +
                               " --float " + pfm.string() + " --stats " + stats.string(),
                           dir_);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        std::ifstream in(pfm, std::ios::binary);
        std::stringstream bytes;
        bytes << in.rdbuf();
        std::ifstream json(stats);
        return std::pair{bytes.str(), nlohmann::json::parse(json)};
    };
    auto [a, stats] = render_spp("a", "5");
    auto [b, b_stats] = render_spp("b", "5");
    const std::string c = render_spp("c", "6").first;
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(a, b);
    EXPECT_EQ(b_stats["shadow_rays"], stats["shadow_rays"]);
    EXPECT_NE(a, c);
    EXPECT_EQ(stats["spp"], 4);
    EXPECT_EQ(stats["spp_method"], "reconstruction");
    EXPECT_GT(stats["lightcuts_computed"].get<uint64_t>(), 0u);
    EXPECT_GT(stats["reconstruction_cuts"].get<uint64_t>(), 0u);
    EXPECT_EQ(stats["nonfinite_pixels"], 0);
    EXPECT_LE(stats["rel_err_mean"].get<double>(), 0.05);
}

TEST_F(RenderCommand, TileStrideWritesTheFullReferencesTilesAndSaysSo) {
    // --tile-stride 2 on 64x48: the middle 8x8 tile of every 2x2 block of
    // tiles, side by side in a 32x24 image, each pixel the full frame's.
    auto render_reference = [&](const std::string& tag, const std::string& flags) {
        CommandRun r = run(scene_path_.string() + " --mode reference --size 64x48 " + flags +
                               " -o " + (dir_ / (tag + ".png")).string() + " --float " +
                               (dir_ / (tag + ".pfm")).string() + " --stats " +
                               (dir_ / (tag + ".json")).string(),
                           dir_);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        std::ifstream json(dir_ / (tag + ".json"));
        return std::pair{read_pfm(dir_ / (tag + ".pfm")), nlohmann::json::parse(json)};
    };
    auto [full, full_stats] = render_reference("full", "");
    auto [tiles, stats] = render_reference("tiles", "--tile-stride 2");
    ASSERT_TRUE(full.ok() && tiles.ok());
    ASSERT_EQ(tiles->width, 32u);
    ASSERT_EQ(tiles->height, 24u);
    EXPECT_EQ(stats["pixel_stride"], 2);
    EXPECT_EQ(stats["stride_tile"], 8);
    EXPECT_EQ(stats["width"], 32);
    EXPECT_FALSE(full_stats.contains("stride_tile"));
    size_t differ = 0;
    for (uint32_t y = 0; y < 24; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            // Tile (i, j) of the strided image is tile (2i + 1, 2j + 1) of the full one.
            const uint32_t fx = (2 * (x / 8) + 1) * 8 + x % 8, fy = (2 * (y / 8) + 1) * 8 + y % 8;
            const size_t at = 3 * (size_t(y) * 32 + x), full_at = 3 * (size_t(fy) * 64 + fx);
            for (int c = 0; c < 3; ++c) differ += tiles->rgb[at + c] != full->rgb[full_at + c];
        }
    EXPECT_EQ(differ, 0u);

    std::filesystem::path png = dir_ / "x.png";
    const std::string reference = scene_path_.string() + " --mode reference --size 64x48 ";
    CommandRun both = run(reference + "--tile-stride 2 --pixel-stride 2 -o " + png.string(), dir_);
    EXPECT_NE(both.exit_code, 0);
    EXPECT_NE(both.output.find("not both"), std::string::npos) << both.output;
    CommandRun uneven = run(reference + "--tile-stride 4 -o " + png.string(), dir_);
    EXPECT_NE(uneven.exit_code, 0);
    EXPECT_NE(uneven.output.find("does not divide"), std::string::npos) << uneven.output;
}

TEST_F(RenderCommand, ErrorsNameTheProblem) {
    std::filesystem::path png = dir_ / "x.png";
    CommandRun no_tree = run(scene_path_.string() + " --mode lightcuts -o " + png.string(), dir_);
    EXPECT_NE(no_tree.exit_code, 0);
    EXPECT_NE(no_tree.output.find("needs a light tree"), std::string::npos) << no_tree.output;

    CommandRun bad_camera =
        run(scene_path_.string() + " --camera-index 7 -o " + png.string(), dir_);
    EXPECT_NE(bad_camera.exit_code, 0);
    EXPECT_NE(bad_camera.output.find("--camera-index 7"), std::string::npos) << bad_camera.output;

    CommandRun bad_size = run(scene_path_.string() + " --size 0x10 -o " + png.string(), dir_);
    EXPECT_NE(bad_size.exit_code, 0);
    EXPECT_NE(bad_size.output.find("--size"), std::string::npos) << bad_size.output;

    std::filesystem::path garbage = dir_ / "garbage.lcut";
    std::ofstream(garbage) << "not a dump";
    CommandRun bad_tree = run(
        scene_path_.string() + " --tree " + garbage.string() + " --mode cuts -o " + png.string(),
        dir_);
    EXPECT_NE(bad_tree.exit_code, 0);
    EXPECT_NE(bad_tree.output.find("garbage.lcut"), std::string::npos) << bad_tree.output;

    CommandRun missing_scene = run((dir_ / "nope.gltf").string() + " -o " + png.string(), dir_);
    EXPECT_NE(missing_scene.exit_code, 0);
    EXPECT_NE(missing_scene.output.find("nope.gltf"), std::string::npos) << missing_scene.output;
    EXPECT_FALSE(std::filesystem::exists(png));
}

}  // namespace
}  // namespace lc::client
