// The editor's real-time modes in a real window (xvfb-run) driven by a
// scripted session (`view --script`), once per mode of kRealtimeModes: a
// still camera whose history grows and whose image converges towards the
// reference mode's, and a camera moving along an orbit whose frames keep
// coming, finite. A new real-time mode is one more entry of the list.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "editor_client/render/output/image_io.h"
#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/sweeps/camera_path.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "render_test_support.h"
#include "test_paths.h"

namespace lc::client {
namespace {

// A real-time mode as the editor's script selects it: its name and the
// commands that set its own controls.
struct RealtimeModeCase {
    const char* mode;
    const char* setup;
    // The mean of still frames converges to the exact answer; else the bound its bias stays under.
    bool unbiased_mean;
    double biased_bound;
};
const RealtimeModeCase kRealtimeModes[] = {
    {"realtime", "realtime-cut 8\n", true, 0.0},
    {"realtime", "realtime-cut 16\nrealtime-rays 1\n", true, 0.0},
    // ReSTIR at its defaults combines reservoirs with 1/M weights (biased): its
    // still mean settles near, not at, the reference (relative MSE 0.025 after
    // 2 frames, 0.062 after 32: temporal reuse brings its bias in).
    {"restir", "", false, 0.1},
};
// Named in test output by its mode, not by its pointers' bytes.
void PrintTo(const RealtimeModeCase& c, std::ostream* out) { *out << c.mode; }

class RealtimeScript : public ::testing::TestWithParam<RealtimeModeCase> {
protected:
    void SetUp() override {
        if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed";
        std::unique_ptr<vk::Context> probe;
        LC_REQUIRE_VULKAN(probe);
        dir_ = test::make_temp_dir("editor-realtime-script");
        scene_ = test::lit_room(11);
        scene_path_ = dir_ / "room.gltf";
        ASSERT_TRUE(write_scene_gltf(scene_, scene_path_).ok());
        tree_ = test::write_tree_dump(scene_, dir_);
    }
    void TearDown() override {
        if (!dir_.empty()) std::filesystem::remove_all(dir_);
    }

    // Runs the view on `script` in `mode`; its exit status and output.
    std::pair<int, std::string> run_view(const std::string& name, const std::string& mode,
                                         const std::string& script) {
        const std::filesystem::path script_path = dir_ / (name + ".txt");
        std::ofstream(script_path) << script;
        const std::filesystem::path log = dir_ / (name + ".log");
        const std::string command = "xvfb-run -a " + (test::bin_dir() / "editor_client").string() + " view " +
                                    scene_path_.string() + " --tree " + tree_.string() + " --mode " + mode +
                                    " --size 64x48 --exposure 1 --validation --script " + script_path.string() +
                                    " > " + log.string() + " 2>&1";
        const int status = std::system(command.c_str());
        return {status, test::read_text(log)};
    }

    FloatImage read(const std::string& name) {
        Result<FloatImage> image = read_pfm(dir_ / name);
        EXPECT_TRUE(image.ok()) << name << ": " << image.error();
        return image.ok() ? *image : FloatImage{};
    }

    std::filesystem::path dir_;
    Scene scene_;
    std::filesystem::path scene_path_;
    std::filesystem::path tree_;
};

// The sum of squared differences over the reference's squared sum.
double relative_mse(const FloatImage& image, const FloatImage& reference) {
    double error = 0.0, energy = 0.0;
    for (size_t i = 0; i < image.rgb.size() && i < reference.rgb.size(); ++i) {
        const double d = double(image.rgb[i]) - double(reference.rgb[i]);
        error += d * d;
        energy += double(reference.rgb[i]) * double(reference.rgb[i]);
    }
    return energy > 0.0 ? error / energy : 0.0;
}

// The number after `label` in the view's output (-1: absent).
long number_after(const std::string& text, const std::string& label) {
    const size_t at = text.find(label);
    return at == std::string::npos ? -1 : std::atol(text.c_str() + at + label.size());
}

// Frames the view ran, from its summary line "N frames, last in MODE mode" (-1: absent).
long frames_run(const std::string& text) {
    const size_t at = text.find(" frames, last in ");
    if (at == std::string::npos) return -1;
    const size_t line = text.rfind('\n', at);
    return std::atol(text.c_str() + (line == std::string::npos ? 0 : line + 1));
}

TEST_P(RealtimeScript, StillCameraAccumulatesTowardsTheReference) {
    const RealtimeModeCase mode = GetParam();
    const std::string script = std::string("mode reference\nwait-refined\nsave-view ") + (dir_ / "ref.pfm").string() +
                               "\nmode " + mode.mode + "\n" + mode.setup + "wait-frames 2\nsave-view " +
                               (dir_ / "early.pfm").string() + "\nwait-refined\nwait-frames 16\nsave-view " +
                               (dir_ / "late.pfm").string() + "\nquit\n";
    const auto [status, text] = run_view("still", "reference", script);
    ASSERT_EQ(status, 0) << text;
    EXPECT_NE(text.find(std::string("last in ") + mode.mode + " mode"), std::string::npos) << text;
    EXPECT_NE(text.find(" 0 validation messages"), std::string::npos) << text;
    EXPECT_GE(number_after(text, "realtime history: "), 32) << "the still view's history grows: " << text;
    const FloatImage reference = read("ref.pfm"), early = read("early.pfm"), late = read("late.pfm");
    ASSERT_EQ(late.rgb.size(), reference.rgb.size());
    const double early_error = relative_mse(early, reference), late_error = relative_mse(late, reference);
    EXPECT_GT(early_error, 0.0);
    // At least 16x the frames of a plain mean (the filter aside): far less
    // than the early image's error, whatever the draws.
    if (mode.unbiased_mean)
        EXPECT_LT(late_error, early_error / 2.0) << "the accumulated view converges";
    else
        EXPECT_LT(late_error, mode.biased_bound) << "the accumulated view stays near the reference";
}

TEST_P(RealtimeScript, MovingCameraKeepsFramesComingAndFinite) {
    const RealtimeModeCase mode = GetParam();
    const RenderCamera start = camera_from_scene(scene_.cameras.at(0));
    std::ostringstream script;
    script << mode.setup << "wait-frames 4\n";
    for (const RenderCamera& c : orbit_path(start, 12)) {
        script << "camera " << c.eye.x << ' ' << c.eye.y << ' ' << c.eye.z << ' ' << c.target.x << ' ' << c.target.y
               << ' ' << c.target.z << ' ' << c.yfov * 180.0f / std::numbers::pi_v<float> << "\nwait-frames 1\n";
    }
    script << "save-view " << (dir_ / "moving.pfm").string() << "\nquit\n";
    const auto [status, text] = run_view("moving", mode.mode, script.str());
    ASSERT_EQ(status, 0) << text;
    EXPECT_NE(text.find(" 0 validation messages"), std::string::npos) << text;
    EXPECT_GE(frames_run(text), 4 + 12) << "a frame at least per camera step: " << text;
    EXPECT_LE(number_after(text, "realtime history: "), 12) << "the moving view's history is reset or short: "
                                                             << text;
    const FloatImage moving = read("moving.pfm");
    ASSERT_FALSE(moving.rgb.empty());
    double sum = 0.0;
    for (float v : moving.rgb) {
        ASSERT_TRUE(std::isfinite(v)) << "a moving frame with a non-finite pixel";
        sum += v;
    }
    EXPECT_GT(sum, 0.0) << "the moving view is lit";
}

INSTANTIATE_TEST_SUITE_P(Modes, RealtimeScript, ::testing::ValuesIn(kRealtimeModes),
                         [](const ::testing::TestParamInfo<RealtimeModeCase>& info) {
                             return std::string(info.param.mode) + std::to_string(info.index);
                         });

}  // namespace
}  // namespace lc::client
