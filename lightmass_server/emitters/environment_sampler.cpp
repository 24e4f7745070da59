#include "lightmass_server/emitters/environment_sampler.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <numbers>

#include "lightcuts/seeded_mixer.h"
#include "lightcuts/status_macros.h"

namespace lc::bake {
namespace {

constexpr glm::dvec3 kLuminance{0.2126, 0.7152, 0.0722};  // Rec. 709
// Salts keep the map's and the sun's draws apart for one seed.
constexpr uint64_t kMapSalt = 0x656E762D6D617031ull;
constexpr uint64_t kSunSalt = 0x656E762D73756E31ull;
constexpr int kBisectionSteps = 48;
// Below this extent (texels) a stratum is a point: its lights share it.
constexpr double kSmallestStratum = 1e-9;

// Integrals of radiance times solid angle over rectangles of texel space,
// from a summed-area table. Inside a texel the integrand is constant, so the
// table's bilinear interpolation is exact at fractional corners too.
class RadianceIntegral {
public:
    // Stops early, the table partial and unusable, once `poll` says the bake must stop.
    // The table (24 bytes a texel: 805 MB for 8192 x 4096) is written row by
    // row as it is computed, never zero-filled whole first, so a stop is seen
    // within one row's work.
    RadianceIntegral(const EquirectMap& map, StopPoll& poll) : width_(map.width), height_(map.height) {
        sums_.reserve(size_t(width_ + 1) * (height_ + 1));
        sums_.resize(width_ + 1, glm::dvec3(0.0));
        for (uint32_t y = 0; y < height_; ++y) {
            if (poll()) return;  // partial: the caller asks the poll again before using it
            const double solid_angle = equirect_texel_solid_angle(y, width_, height_);
            glm::dvec3 row(0.0);
            sums_.push_back(glm::dvec3(0.0));
            for (uint32_t x = 0; x < width_; ++x) {
                row += glm::dvec3(map.at(x, y)) * solid_angle;
                sums_.push_back(sum(x + 1, y) + row);
            }
        }
    }

    glm::dvec3 over(double x0, double x1, double y0, double y1) const {
        return glm::max(cumulative(x1, y1) - cumulative(x0, y1) - cumulative(x1, y0) + cumulative(x0, y0),
                        glm::dvec3(0.0));
    }
    double power(double x0, double x1, double y0, double y1) const {
        return glm::dot(kLuminance, over(x0, x1, y0, y1));
    }

private:
    glm::dvec3& sum(uint32_t x, uint32_t y) { return sums_[size_t(y) * (width_ + 1) + x]; }
    const glm::dvec3& sum(uint32_t x, uint32_t y) const { return sums_[size_t(y) * (width_ + 1) + x]; }
    glm::dvec3 cumulative(double x, double y) const {
        const auto i = std::min(uint32_t(x), width_ - 1);
        const auto j = std::min(uint32_t(y), height_ - 1);
        const double fx = x - i, fy = y - j;
        const glm::dvec3 s00 = sum(i, j), s10 = sum(i + 1, j), s01 = sum(i, j + 1), s11 = sum(i + 1, j + 1);
        return s00 + fx * (s10 - s00) + fy * (s01 - s00) + fx * fy * (s11 - s10 - s01 + s00);
    }

    uint32_t width_, height_;
    std::vector<glm::dvec3> sums_;
};

struct Stratum {
    double x0, x1, y0, y1;
    uint32_t lights;
    uint32_t first_slot;  // the stratum's lights take slots [first_slot, first_slot + lights)
};

// The t in [lo, hi] where power_to(t) reaches target (power_to increasing).
template <typename PowerTo>
double bisect(double lo, double hi, double target, const PowerTo& power_to) {
    for (int step = 0; step < kBisectionSteps; ++step) {
        const double mid = 0.5 * (lo + hi);
        if (power_to(mid) < target) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

// A point of the stratum drawn with density proportional to luminous power:
// x from the marginal, then y from the texel column x falls in.
glm::dvec2 draw_point(const RadianceIntegral& integral, const Stratum& s, uint32_t width, SplitMix64& random) {
    const double total = integral.power(s.x0, s.x1, s.y0, s.y1);
    const double x = bisect(s.x0, s.x1, random.uniform() * total,
                            [&](double t) { return integral.power(s.x0, t, s.y0, s.y1); });
    const double column = std::min(std::floor(x), double(width - 1));
    const double c0 = std::max(s.x0, column), c1 = std::min(s.x1, column + 1.0);
    const double strip = c1 > c0 ? integral.power(c0, c1, s.y0, s.y1) : 0.0;
    const double u = random.uniform();
    const double y = strip > 0.0 ? bisect(s.y0, s.y1, u * strip,
                                          [&](double t) { return integral.power(c0, c1, s.y0, t); })
                                 : s.y0 + u * (s.y1 - s.y0);
    return {x, y};
}

Guid draw_guid(SplitMix64& random) {
    const uint64_t high = random.next(), low = random.next();
    return Guid{uint32_t(high >> 32), uint32_t(high), uint32_t(low >> 32), uint32_t(low)};
}

// A directional light arriving from `towards_light` with irradiance `lux` (RGB).
SceneLight directional_light(const glm::dvec3& towards_light, const glm::dvec3& lux, const Guid& guid) {
    const double peak = std::max({lux.x, lux.y, lux.z});
    SceneLight light;
    light.guid = guid;
    light.type = LightType::kDirectional;
    light.direction = glm::vec3(-glm::normalize(towards_light));
    light.color = glm::vec3(lux / peak);
    light.intensity = float(peak);
    return light;
}

}  // namespace

std::vector<SceneLight> sample_equirect_map(const EquirectMap& map, double rotation, double intensity,
                                            uint32_t count, uint64_t seed, IndexRange slots,
                                            const BakeStop* stop) {
    std::vector<SceneLight> lights;
    if (map.empty() || count == 0 || !(intensity > 0.0)) return lights;
    StopPoll poll(stop);
    const RadianceIntegral integral(map, poll);
    if (poll()) return lights;
    const double width = map.width, height = map.height;
    std::vector<Stratum> stack;
    if (integral.power(0.0, width, 0.0, height) > 0.0) stack.push_back({0.0, width, 0.0, height, count, 0});
    while (!stack.empty() && !poll()) {
        const Stratum s = stack.back();
        stack.pop_back();
        // Strata wholly outside this share are never split: a share costs its part.
        if (s.first_slot >= slots.end || uint64_t(s.first_slot) + s.lights <= slots.begin) continue;
        const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
        if (s.lights == 1 || std::max(dx, dy) < kSmallestStratum) {
            const glm::dvec3 lux = integral.over(s.x0, s.x1, s.y0, s.y1) * (intensity / s.lights);
            for (uint32_t k = 0; k < s.lights; ++k) {
                if (!slots.contains(s.first_slot + k)) continue;
                // Each slot draws from its own stream: any share of the slots draws the same.
                SplitMix64 random(mix64(seed ^ kMapSalt ^ mix64(uint64_t(s.first_slot) + k + 1)));
                const glm::dvec2 p = draw_point(integral, s, map.width, random);
                const glm::dvec3 towards = equirect_direction(p.x / width, p.y / height, rotation);
                lights.push_back(directional_light(towards, lux, draw_guid(random)));
            }
            continue;
        }
        // Split the longer side (as an angle on the sphere) where half the
        // lights' share of the power lies on either side: equal-power strata.
        const double sin_theta = std::sin(std::numbers::pi * 0.5 * (s.y0 + s.y1) / height);
        const bool split_x = dx / width * 2.0 * sin_theta >= dy / height;
        const double power = integral.power(s.x0, s.x1, s.y0, s.y1);
        Stratum a = s, b = s;
        a.lights = s.lights / 2;
        b.lights = s.lights - a.lights;
        b.first_slot = s.first_slot + a.lights;
        const double target = power * a.lights / s.lights;
        if (split_x)
            a.x1 = b.x0 = bisect(s.x0, s.x1, target, [&](double t) { return integral.power(s.x0, t, s.y0, s.y1); });
        else
            a.y1 = b.y0 = bisect(s.y0, s.y1, target, [&](double t) { return integral.power(s.x0, s.x1, s.y0, t); });
        // Rounding can leave a side empty: the other takes its lights.
        const bool a_lit = integral.power(a.x0, a.x1, a.y0, a.y1) > 0.0;
        const bool b_lit = integral.power(b.x0, b.x1, b.y0, b.y1) > 0.0;
        if (!a_lit || !b_lit) {
            Stratum& lit = a_lit ? a : b;
            lit.lights = s.lights;
            lit.first_slot = s.first_slot;
            if (a_lit || b_lit) stack.push_back(lit);
            continue;
        }
        stack.push_back(b);
        stack.push_back(a);
    }
    return lights;
}

std::vector<SceneLight> sample_sun_disc(const SkyParameters& sky, double intensity, uint32_t count, uint64_t seed) {
    std::vector<SceneLight> lights;
    const glm::dvec3 radiance = sun_disc_radiance(sky) * intensity;
    if (count == 0 || !(glm::dot(kLuminance, radiance) > 0.0)) return lights;
    const double cos_radius = std::cos(sun_angular_radius());
    const glm::dvec3 lux = radiance * (2.0 * std::numbers::pi * (1.0 - cos_radius) / count);
    const glm::dvec3 s = sun_direction(sky);
    const glm::dvec3 t1 = glm::normalize(glm::cross(std::abs(s.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0), s));
    const glm::dvec3 t2 = glm::cross(s, t1);
    SplitMix64 random(mix64(seed ^ kSunSalt));
    const double spin = 2.0 * std::numbers::pi * random.uniform();
    // Vogel's spiral over equal solid angles: rings at cos r uniform in [cos R, 1].
    const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
    lights.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        const double cos_r = 1.0 - (1.0 - cos_radius) * (i + 0.5) / count;
        const double sin_r = std::sqrt(std::max(0.0, 1.0 - cos_r * cos_r));
        const double phi = spin + golden_angle * i;
        const glm::dvec3 towards = cos_r * s + sin_r * (std::cos(phi) * t1 + std::sin(phi) * t2);
        lights.push_back(directional_light(towards, lux, draw_guid(random)));
    }
    return lights;
}

Result<EnvironmentLights> sample_environment(const Environment& environment, uint32_t count, uint64_t seed,
                                             uint32_t part, uint32_t parts, const BakeStop* stop) {
    if (count == 0) count = kDefaultEnvironmentLights;
    LC_RETURN_IF_ERROR(validate_environment_light_count(environment, count));
    EnvironmentLights out;
    const double rotation = double(environment.rotation_deg) * std::numbers::pi / 180.0;
    if (environment.has_sky()) {
        const SkyParameters& sky = *environment.sky;
        const auto sun_lights =
            uint32_t(std::clamp(std::round(count * kSunShareOfSkyLights), 1.0, double(count - 1)));
        if (part == 0) out.lights = sample_sun_disc(sky, environment.intensity, sun_lights, seed);
        const size_t sun_made = out.lights.size();
        const EquirectMap raster = rasterize_sky(sky, kSkyRasterWidth, kSkyRasterHeight);
        std::vector<SceneLight> sky_lights =
            sample_equirect_map(raster, 0.0, environment.intensity, count - sun_lights, seed,
                                share_of(count - sun_lights, part, parts), stop);
        out.lights.insert(out.lights.end(), sky_lights.begin(), sky_lights.end());
        char text[160];
        std::snprintf(text, sizeof(text),
                      "sun and sky: simulated (%zu sun + %zu sky lights; sun at %.1f deg elevation, %.1f deg "
                      "azimuth, turbidity %.1f)",
                      sun_made, sky_lights.size(), sky.elevation_deg, sky.azimuth_deg, sky.turbidity);
        out.census = text;
    } else {
        out.lights = sample_equirect_map(environment.map, rotation, environment.intensity, count, seed,
                                         share_of(count, part, parts), stop);
        out.census = "environment: simulated (" + std::to_string(environment.map.width) + " x " +
                     std::to_string(environment.map.height) + " map, " + std::to_string(out.lights.size()) +
                     " lights)";
    }
    if (stop_requested(stop)) return stop->reason("environment sampling");
    if (out.lights.empty()) out.census = (environment.has_sky() ? "sun and sky" : std::string("environment")) +
                                         ": skipped (it emits no light)";
    return out;
}

}  // namespace lc::bake
