#include "editor_client/render/settings/render_settings.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "lightcuts/device/limits.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    size_t start = 0;
    while (true) {
        size_t end = text.find(separator, start);
        parts.push_back(text.substr(start, end == std::string_view::npos ? end : end - start));
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    return parts;
}

std::optional<float> parse_float(std::string_view text) {
    // std::from_chars for float is in GCC 11+; strtof needs a terminated copy.
    std::string copy(text);
    if (copy.empty()) return std::nullopt;
    char* end = nullptr;
    float value = std::strtof(copy.c_str(), &end);
    if (end != copy.c_str() + copy.size() || !std::isfinite(value)) return std::nullopt;
    return value;
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string number_text(float value) {
    if (std::isinf(value)) return value > 0.0f ? "inf" : "-inf";
    char text[32];
    std::snprintf(text, sizeof(text), "%g", double(value));
    return text;
}

}  // namespace

const char* render_mode_name(RenderMode mode) { return name_in(kRenderModeNames, mode); }

std::optional<RenderMode> parse_render_mode(std::string_view text) {
    return value_in(kRenderModeNames, text);
}

const char* criterion_name(CutCriterion criterion) { return name_in(kCriterionNames, criterion); }

std::optional<CutCriterion> parse_criterion(std::string_view text) { return value_in(kCriterionNames, text); }

const char* bound_search_name(BoundSearch search) { return name_in(kBoundSearchNames, search); }

std::optional<BoundSearch> parse_bound_search(std::string_view text) {
    return value_in(kBoundSearchNames, text);
}

const char* primary_visibility_name(PrimaryVisibility primary) {
    return name_in(kPrimaryVisibilityNames, primary);
}

std::optional<PrimaryChoice> parse_primary_choice(std::string_view text) {
    return value_in(kPrimaryChoiceNames, text);
}

const char* representatives_name(Representatives representatives) {
    return name_in(kRepresentativesNames, representatives);
}

std::optional<Representatives> parse_representatives(std::string_view text) {
    return value_in(kRepresentativesNames, text);
}

Result<RenderCamera> parse_camera(std::string_view text) {
    std::vector<std::string_view> parts = split(text, ',');
    if (parts.size() != 7)
        return make_error(
            "--camera expects 7 comma-separated numbers ex,ey,ez,tx,ty,tz,fovy, got " +
            std::to_string(parts.size()));
    float v[7];
    for (size_t i = 0; i < 7; ++i) {
        std::optional<float> value = parse_float(parts[i]);
        if (!value)
            return make_error("--camera value " + std::to_string(i + 1) + " ('" +
                              std::string(parts[i]) + "') is not a finite number");
        v[i] = *value;
    }
    RenderCamera camera;
    camera.eye = {v[0], v[1], v[2]};
    camera.target = {v[3], v[4], v[5]};
    if (!(v[6] > 0.0f && v[6] < 180.0f))
        return make_error("--camera fovy must be in (0, 180) degrees, got " + std::to_string(v[6]));
    camera.yfov = v[6] * std::numbers::pi_v<float> / 180.0f;
    if (glm::length(camera.target - camera.eye) <= 0.0f)
        return make_error("--camera eye and target are the same point");
    return camera;
}

Result<std::pair<uint32_t, uint32_t>> parse_size(std::string_view text) {
    size_t x = text.find_first_of("xX");
    if (x == std::string_view::npos)
        return make_error("--size expects WxH, got '" + std::string(text) + "'");
    uint32_t w = 0, h = 0;
    std::string_view ws = text.substr(0, x), hs = text.substr(x + 1);
    auto [pw, ew] = std::from_chars(ws.data(), ws.data() + ws.size(), w);
    auto [ph, eh] = std::from_chars(hs.data(), hs.data() + hs.size(), h);
    if (ew != std::errc() || eh != std::errc() || pw != ws.data() + ws.size() ||
        ph != hs.data() + hs.size())
        return make_error("--size expects WxH with whole numbers, got '" + std::string(text) + "'");
    if (w == 0 || h == 0 || w > kMaxImageSide || h > kMaxImageSide)
        return make_error("--size " + std::string(text) + " is outside 1x1 .. 16384x16384");
    return std::pair{w, h};
}

Status validate(const RenderSettings& settings, const ValidationContext& context) {
    if (settings.width == 0 || settings.height == 0 || settings.width > kMaxImageSide ||
        settings.height > kMaxImageSide)
        return make_error("image size " + std::to_string(settings.width) + "x" +
                          std::to_string(settings.height) + " is outside 1x1 .. " +
                          std::to_string(kMaxImageSide) + "x" + std::to_string(kMaxImageSide));
    if (mode_needs_tree(settings.mode) && !context.has_tree)
        return make_error(std::string("mode '") + render_mode_name(settings.mode) +
                          "' needs a light tree (--tree, --server or --spawn-server)");
    if (settings.criterion != CutCriterion::kRadius && settings.criterion != CutCriterion::kBound)
        return make_error("unknown cut criterion " +
                          std::to_string(static_cast<int>(settings.criterion)));
    if (settings.bound_search != BoundSearch::kWalk && settings.bound_search != BoundSearch::kHeap)
        return make_error("unknown bound search " +
                          std::to_string(static_cast<int>(settings.bound_search)));
    if (settings.share_cuts && mode_searches_cuts(settings.mode) &&
        (settings.criterion != CutCriterion::kBound || settings.bound_search != BoundSearch::kWalk))
        return make_error("shared cuts need the bound criterion's walk search");
    if (settings.representatives != Representatives::kTree &&
        settings.representatives != Representatives::kPixel &&
        settings.representatives != Representatives::kImportance)
        return make_error("unknown representatives " +
                          std::to_string(static_cast<int>(settings.representatives)));
    if (settings.representatives != Representatives::kTree && mode_searches_cuts(settings.mode) &&
        settings.criterion != CutCriterion::kBound)
        return make_error("per-pixel representatives need the bound criterion");
    // The heap reuses a parent's evaluation per unit intensity, which the
    // importance draw's probabilities do not keep.
    if (settings.representatives == Representatives::kImportance && mode_searches_cuts(settings.mode) &&
        settings.bound_search != BoundSearch::kWalk)
        return make_error("importance-drawn representatives need the walk search");
    const float ratio = settings.error_ratio;
    if (!std::isfinite(ratio) || ratio < context.min_error_ratio || ratio > context.max_error_ratio)
        return make_error("error ratio " + number_text(ratio) + " is outside [" +
                          number_text(context.min_error_ratio) + ", " +
                          number_text(context.max_error_ratio) + "]");
    if (settings.max_cut < 1 || settings.max_cut > kMaxGpuCut)
        return make_error("max cut " + std::to_string(settings.max_cut) + " is outside 1 .. " +
                          std::to_string(kMaxGpuCut));
    if (settings.realtime_cut < 1 || settings.realtime_cut > kMaxStochasticCut)
        return make_error("real-time cut " + std::to_string(settings.realtime_cut) +
                          " is outside 1 .. " + std::to_string(kMaxStochasticCut));
    if (settings.realtime_rays > kMaxStochasticRays)
        return make_error("real-time shadow rays " + std::to_string(settings.realtime_rays) +
                          " is outside 0 .. " + std::to_string(kMaxStochasticRays) +
                          " (0: one per cut node)");
    LC_RETURN_IF_ERROR(validate(settings.restir));
    if (settings.reconstruction_block == 1 || settings.reconstruction_block > kMaxReconstructionBlock)
        return make_error("reconstruction block " + std::to_string(settings.reconstruction_block) +
                          " is outside 2 .. " + std::to_string(kMaxReconstructionBlock) + " (0: off)");
    if (settings.reconstruction_cap < 1 || settings.reconstruction_cap > kMaxGpuCut)
        return make_error("reconstruction cap " + std::to_string(settings.reconstruction_cap) +
                          " is outside 1 .. " + std::to_string(kMaxGpuCut));
    if (settings.reconstruction_block > 0 && mode_searches_cuts(settings.mode)) {
        if (settings.criterion != CutCriterion::kBound || settings.bound_search != BoundSearch::kWalk)
            return make_error("reconstruction cuts need the bound criterion's walk search");
        if (settings.share_cuts) return make_error("reconstruction cuts and shared cuts exclude each other");
    }
    const RenderCamera& c = settings.camera;
    if (!finite(c.eye) || !finite(c.target) || !finite(c.up))
        return make_error("the camera has a non-finite coordinate");
    if (!std::isfinite(c.yfov) || !(c.yfov > 0.0f && c.yfov < kMaxFieldOfView))
        return make_error("the camera's field of view " + number_text(c.yfov) +
                          " rad is outside (0, " + number_text(kMaxFieldOfView) + ")");
    if (glm::length(c.target - c.eye) <= 0.0f)
        return make_error("the camera's eye and target coincide");
    if (!std::isfinite(settings.exposure) || settings.exposure < 0.0f)
        return make_error("exposure " + number_text(settings.exposure) +
                          " is not a finite number >= 0");
    const glm::vec2 o = settings.pixel_offset;
    if (!(std::abs(o.x) <= 0.5f && std::abs(o.y) <= 0.5f))
        return make_error("pixel offset (" + number_text(o.x) + ", " + number_text(o.y) +
                          ") is outside [-0.5, 0.5]");
    if (settings.corner_grid && (settings.width < 2 || settings.height < 2))
        return make_error("a corner grid needs at least 2x2 corners");
    return Ok{};
}

RenderCamera frame_scene_bounds(const Scene& scene, float aspect) {
    // Frame the geometry when there is some (lights may sit far outside it),
    // else the scene bounds.
    glm::vec3 lo = scene.bounds_min, hi = scene.bounds_max;
    bool any_vertex = false;
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            lo = any_vertex ? glm::min(lo, p) : p;
            hi = any_vertex ? glm::max(hi, p) : p;
            any_vertex = true;
        }
    }
    RenderCamera camera;
    glm::vec3 center = 0.5f * (lo + hi);
    float radius = 0.5f * glm::length(hi - lo);
    if (!(radius > 1e-6f) || !std::isfinite(radius)) radius = 1.0f;
    camera.yfov = 0.8f;
    // Fit the bounding sphere in the narrower of the two fields of view.
    float half_fov = 0.5f * camera.yfov;
    if (aspect < 1.0f) half_fov = std::atan(std::tan(half_fov) * aspect);
    float distance = radius / std::sin(half_fov);
    // From +Z (where glTF models face) and a little above.
    glm::vec3 view_dir = glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));
    camera.target = center;
    camera.eye = center + view_dir * distance;
    return camera;
}

RenderCamera camera_from_scene(const Camera& camera) {
    RenderCamera out;
    out.eye = camera.eye;
    out.target = camera.target;
    out.up = camera.up;
    out.yfov = camera.yfov;
    return out;
}

}  // namespace lc::client
