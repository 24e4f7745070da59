// validate(RenderSettings): the one check the commands, the editor session
// and the renderer share.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "editor_client/render/settings/render_settings.h"

namespace lc::client {
namespace {

// The error of `settings` (empty when they are valid).
std::string error_of(const RenderSettings& settings, const ValidationContext& context = {}) {
    Status status = validate(settings, context);
    return status ? std::string() : status.error();
}

TEST(ValidateRenderSettings, DefaultsAreValid) {
    EXPECT_EQ(error_of(RenderSettings{}), "");
}

TEST(ValidateRenderSettings, EachBadFieldIsNamed) {
    RenderSettings s;
    s.width = 0;
    EXPECT_NE(error_of(s).find("image size 0x512"), std::string::npos) << error_of(s);
    s = {};
    s.height = kMaxImageSide + 1;
    EXPECT_NE(error_of(s).find("image size"), std::string::npos) << error_of(s);
    s = {};
    s.error_ratio = -0.5f;
    EXPECT_NE(error_of(s).find("error ratio -0.5"), std::string::npos) << error_of(s);
    s.error_ratio = std::nanf("");
    EXPECT_NE(error_of(s).find("error ratio"), std::string::npos) << error_of(s);
    s = {};
    s.max_cut = 0;
    EXPECT_NE(error_of(s).find("max cut 0"), std::string::npos) << error_of(s);
    s.max_cut = kMaxGpuCut + 1;
    EXPECT_NE(error_of(s).find("max cut"), std::string::npos) << error_of(s);
    s = {};
    s.camera.eye.y = std::numeric_limits<float>::infinity();
    EXPECT_NE(error_of(s).find("non-finite"), std::string::npos) << error_of(s);
    s = {};
    s.camera.yfov = 0.0f;
    EXPECT_NE(error_of(s).find("field of view"), std::string::npos) << error_of(s);
    s = {};
    s.camera.target = s.camera.eye;
    EXPECT_NE(error_of(s).find("eye and target"), std::string::npos) << error_of(s);
    s = {};
    s.exposure = -1.0f;
    EXPECT_NE(error_of(s).find("exposure"), std::string::npos) << error_of(s);
    s = {};
    s.criterion = static_cast<CutCriterion>(7);
    EXPECT_NE(error_of(s).find("criterion"), std::string::npos) << error_of(s);
}

TEST(ValidateRenderSettings, CutModesNeedATree) {
    RenderSettings s;
    s.mode = RenderMode::kCuts;
    EXPECT_EQ(error_of(s, {.has_tree = true}), "");
    EXPECT_NE(error_of(s, {.has_tree = false}).find("needs a light tree"), std::string::npos);
    s.mode = RenderMode::kReference;
    EXPECT_EQ(error_of(s, {.has_tree = false}), "");
}

TEST(ValidateRenderSettings, ErrorRatioRangeComesFromTheCaller) {
    RenderSettings s;
    s.error_ratio = 2.0f;
    EXPECT_EQ(error_of(s), "");
    ValidationContext editor{.has_tree = true, .min_error_ratio = 1e-4f, .max_error_ratio = 1.0f};
    EXPECT_NE(error_of(s, editor).find("[0.0001, 1]"), std::string::npos) << error_of(s, editor);
    s.error_ratio = 0.0f;
    EXPECT_EQ(error_of(s), "");
    EXPECT_NE(error_of(s, editor), "");
    s.error_ratio = 1e-4f;
    EXPECT_EQ(error_of(s, editor), "");
}

}  // namespace
}  // namespace lc::client
