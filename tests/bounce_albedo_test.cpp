// One material model for the bake's bounces and the renderer's shading
// (shading::bounce_albedo): the albedo a bounce reflects is what the shader's
// f_r reflects under diffuse light, integrated here from f_r itself, and a
// closed furnace of one material bounces that energy in both solvers.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "indirect_scenes.h"
#include "lightcuts/material_model.h"
#include "lightmass_server/indirect/radiosity_solver.h"
#include "lightmass_server/indirect/vpl_tracer.h"

namespace lc::bake {
namespace {

constexpr double kPi = std::numbers::pi;

struct Material {
    glm::dvec3 base;
    double metallic;
    double roughness;
};

const Material kMaterials[] = {
    {{1.0, 1.0, 1.0}, 0.0, 1.0},     // white plaster
    {{0.63, 0.065, 0.05}, 0.0, 1.0}, // the Cornell box's red wall
    {{0.5, 0.4, 0.3}, 0.0, 0.5},     // varnished wood
    {{1.0, 0.8, 0.3}, 1.0, 0.4},     // gold
    {{0.9, 0.9, 0.9}, 0.6, 0.7},     // half metal
};

// (1/pi) * the integral over l of f_r(v, l) cos(l), over the hemisphere:
// the light leaving towards v under uniform unit radiance, integrated in
// (h, phi) about the axis `mirror`, h = (1 + cos) / 2 = w^(1 / (n + 1)) so
// that a lobe of exponent n is sampled evenly in w (n = 0: evenly in cos).
template <typename Brdf>
glm::dvec3 directional_albedo(const Brdf& f_r, glm::dvec3 mirror, double n) {
    const glm::dvec3 z(0.0, 0.0, 1.0);
    const glm::dvec3 t = std::abs(mirror.z) < 0.999 ? glm::normalize(glm::cross(z, mirror)) : glm::dvec3(1, 0, 0);
    const glm::dvec3 b = glm::cross(mirror, t);
    const int steps_w = 400, steps_phi = 96;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < steps_w; ++i) {
        const double w = (i + 0.5) / steps_w;
        const double h = std::pow(w, 1.0 / (n + 1.0));
        const double c = 2.0 * h - 1.0, s = std::sqrt(std::max(0.0, 1.0 - c * c));
        // d(omega) = 2 dh dphi, dh = dw / ((n + 1) h^n).
        const double jacobian = 2.0 / ((n + 1.0) * std::pow(h, n));
        for (int k = 0; k < steps_phi; ++k) {
            const double phi = 2.0 * kPi * (k + 0.5) / steps_phi;
            const glm::dvec3 l = c * mirror + s * (std::cos(phi) * t + std::sin(phi) * b);
            if (l.z <= 0.0) continue;
            sum += f_r(l) * l.z * jacobian;
        }
    }
    return sum / double(steps_w) * (2.0 * kPi / steps_phi);
}

// The share of diffuse light the renderer's f_r reflects, averaged over the
// directions it leaves in, cosine-weighted: integral over u in [0, 1] of the
// directional albedo at cos(view) = sqrt(u). The diffuse and glossy terms are
// integrated apart, each sampled where it lies.
glm::dvec3 shader_reflectance(const Material& material) {
    const shading::SurfaceMaterial m = shading::surface_material(material.base, material.metallic, material.roughness);
    const glm::dvec3 normal(0.0, 0.0, 1.0);
    const int steps_u = 96;
    glm::dvec3 sum(0.0);
    for (int j = 0; j < steps_u; ++j) {
        const double mu = std::sqrt((j + 0.5) / steps_u);
        const glm::dvec3 eye(std::sqrt(1.0 - mu * mu), 0.0, mu);
        const glm::dvec3 mirror = shading::mirror_direction(normal, glm::dvec3(0.0), eye);
        auto diffuse = [&](glm::dvec3 l) { return shading::brdf(m.diffuse, glm::dvec3(0.0), m.exponent, mirror, l); };
        auto glossy = [&](glm::dvec3 l) {
            return shading::brdf(glm::dvec3(0.0), m.specular, m.exponent, mirror, l);
        };
        sum += directional_albedo(diffuse, normal, 0.0);
        if (shading::has_lobe(m.specular, m.exponent)) sum += directional_albedo(glossy, mirror, m.exponent);
    }
    return sum / double(steps_u);
}

TEST(BounceAlbedo, IsWhatTheShadersBrdfReflectsUnderDiffuseLight) {
    for (const Material& material : kMaterials) {
        const glm::dvec3 integrated = shader_reflectance(material);
        const glm::dvec3 bounce = shading::bounce_albedo(material.base, material.metallic, material.roughness);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(bounce[c] / integrated[c], 1.0, 1e-3)
                << "base " << material.base[c] << " metallic " << material.metallic << " roughness "
                << material.roughness << " channel " << c;
        }
    }
}

TEST(BounceAlbedo, RoughMaterialsReflectTheirDiffuseAndSpecularTerms) {
    // Roughness 1: 0.96 (1 - metallic) base + mix(0.04, base, metallic).
    const glm::dvec3 red = shading::bounce_albedo({0.63, 0.065, 0.05}, 0.0, 1.0);
    EXPECT_NEAR(red.x, 0.96 * 0.63 + 0.04, 1e-12);
    EXPECT_NEAR(red.y, 0.96 * 0.065 + 0.04, 1e-12);
    const glm::dvec3 half = shading::bounce_albedo({0.5, 0.5, 0.5}, 0.5, 1.0);
    EXPECT_NEAR(half.x, 0.96 * 0.5 * 0.5 + 0.5 * 0.04 + 0.5 * 0.5, 1e-12);
    // A narrow lobe reflects two thirds of diffuse light on average.
    EXPECT_NEAR(shading::lobe_hemispherical_albedo(1e6), 2.0 / 3.0, 1e-6);
    EXPECT_DOUBLE_EQ(shading::lobe_hemispherical_albedo(0.0), 1.0);
    // The server's float version of the same.
    SurfaceMaterial server{glm::vec3(0.63f, 0.065f, 0.05f), glm::vec3(0.0f)};
    EXPECT_NEAR(bounce_albedo(server).x, 0.96f * 0.63f + 0.04f, 1e-6f);
}

// Every wall emits E = pi L_e and reflects rho (the renderer's, integrated
// from its f_r). VPLs: the reflected power is E A rho / (1 - rho), and each
// bounce carries rho times the one before; radiosity: B = E / (1 - rho).
TEST(BounceAlbedo, AFurnaceOfOneMaterialBouncesWhatTheRendererReflects) {
    const double area = 6.0, emitted = kPi * area;
    for (const Material& material : {kMaterials[1], kMaterials[2], kMaterials[3]}) {
        const glm::dvec3 rho = shader_reflectance(material);
        SurfaceMaterial m{glm::vec3(material.base), glm::vec3(1.0f), float(material.metallic),
                          float(material.roughness)};
        SceneGeometry g = test::closed_box(m);
        auto caster = RayCaster::build(g, 1);
        ASSERT_TRUE(caster.ok());

        VplOptions vpl;
        vpl.particle_count = 40000;
        vpl.seed = 5;
        auto traced = trace_vpls(g, *caster, {}, vpl, {});
        ASSERT_TRUE(traced.ok()) << traced.error();
        std::vector<glm::dvec3> per_bounce(3, glm::dvec3(0.0));
        glm::dvec3 total(0.0);
        for (const IndirectLight& l : traced->lights) {
            total += glm::dvec3(l.power);
            if (l.bounce <= 2) per_bounce[l.bounce] += glm::dvec3(l.power);
        }

        RadiosityOptions options;
        options.patch_size = 0.5f;
        options.tolerance = 1e-4;
        auto solved = solve_radiosity(g, *caster, {}, options, {});
        ASSERT_TRUE(solved.ok()) << solved.error();
        glm::dvec3 reflected(0.0);
        for (const IndirectLight& l : solved->lights) reflected += glm::dvec3(l.power);

        for (int c = 0; c < 3; ++c) {
            const double series = emitted * rho[c] / (1.0 - rho[c]);
            std::printf("base %.3f metallic %.1f roughness %.1f: rho %.4f, vpl %.4f radiosity %.4f of the series\n",
                        material.base[c], material.metallic, material.roughness, rho[c], total[c] / series,
                        reflected[c] / series);
            EXPECT_NEAR(per_bounce[1][c] / (emitted * rho[c]), 1.0, 2e-3) << "channel " << c;
            EXPECT_NEAR(per_bounce[2][c] / per_bounce[1][c] / rho[c], 1.0, 0.02) << "channel " << c;
            EXPECT_NEAR(total[c] / series, 1.0, 0.02) << "channel " << c;
            EXPECT_NEAR(reflected[c] / series, 1.0, 0.01) << "channel " << c;
        }
    }
}

}  // namespace
}  // namespace lc::bake
