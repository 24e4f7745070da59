// The material model (material_model.h): glTF parameters to diffuse + lobe,
// the lobe's normalisation, and the bound criterion's material bound against
// the exact maximum of f_r over a cluster's box in 10^6 random configurations.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/material_model.h"
#include "lightcuts/tree/light_tree.h"

namespace lc::client {
namespace {

using shading::glossy_lobe;
using shading::lobe_exponent;
using shading::surface_material;

TEST(MaterialModel, RoughMaterialsShadeAsLambert) {
    // Roughness 1: n = 0, the lobe is the constant 1/pi and joins the diffuse term.
    EXPECT_EQ(lobe_exponent(1.0), 0.0);
    const shading::SurfaceMaterial white = surface_material({1, 1, 1}, 0.0, 1.0);
    EXPECT_EQ(white.specular, glm::dvec3(0.0));
    EXPECT_NEAR(white.diffuse.x, 1.0, 1e-15);  // 0.96 x 1 + 0.04: energy kept
    // glTF's default material (metallic 1, roughness 1) is Lambert on the base colour.
    const shading::SurfaceMaterial metal = surface_material({0.2, 0.5, 0.9}, 1.0, 1.0);
    EXPECT_EQ(metal.specular, glm::dvec3(0.0));
    EXPECT_NEAR(metal.diffuse.y, 0.5, 1e-15);
    EXPECT_DOUBLE_EQ(glossy_lobe(-1.0, 0.0), 1.0 / std::numbers::pi);
    EXPECT_DOUBLE_EQ(glossy_lobe(0.3, 0.0), 1.0 / std::numbers::pi);
}

TEST(MaterialModel, GlossyDielectricAndMetal) {
    const shading::SurfaceMaterial varnish = surface_material({0.5, 0.4, 0.3}, 0.0, 0.3);
    EXPECT_NEAR(varnish.diffuse.x, 0.96 * 0.5, 1e-15);
    EXPECT_NEAR(varnish.specular.z, 0.04, 1e-15);
    EXPECT_NEAR(varnish.exponent, 4.0 / std::pow(0.3, 4) - 4.0, 1e-9);
    const shading::SurfaceMaterial gold = surface_material({1.0, 0.8, 0.3}, 1.0, 0.4);
    EXPECT_EQ(gold.diffuse, glm::dvec3(0.0));
    EXPECT_NEAR(gold.specular.y, 0.8, 1e-15);
    // Below the smallest roughness the lobe stops narrowing, and stays finite.
    EXPECT_EQ(lobe_exponent(0.0), lobe_exponent(shading::kMinRoughness));
    EXPECT_TRUE(std::isfinite(glossy_lobe(1.0, lobe_exponent(0.0))));
}

// With the mirror direction along the normal, the lobe reflects exactly the
// light arriving: the integral of lobe x cos over the hemisphere is 1.
TEST(MaterialModel, LobeReflectsAllLightAtNormalIncidence) {
    for (double roughness : {1.0, 0.9, 0.7, 0.5, 0.3, 0.2, 0.12}) {
        const double n = lobe_exponent(roughness);
        // Integrate in u = (1 + cos) / 2 (the integrand is smooth there):
        // 2 pi * integral over c in [0, 1] of lobe(c) c dc.
        const int steps = 2000000;
        double sum = 0.0;
        for (int k = 0; k < steps; ++k) {
            const double c = (k + 0.5) / steps;
            sum += glossy_lobe(c, n) * c;
        }
        EXPECT_NEAR(2.0 * std::numbers::pi * sum / steps, 1.0, 1e-6) << "roughness " << roughness;
    }
}

TEST(MaterialModel, LobeGrowsTowardsTheMirrorDirection) {
    for (double n : {0.5, 10.0, 500.0, 40000.0}) {
        double last = -1.0;
        for (double c = -1.0; c <= 1.0; c += 1.0 / 64) {
            const double v = glossy_lobe(c, n);
            ASSERT_TRUE(std::isfinite(v));
            ASSERT_GE(v, last) << "n " << n << " c " << c;
            last = v;
        }
    }
}

TEST(MaterialModel, MirrorDirectionReflectsTheView) {
    const glm::dvec3 r = shading::mirror_direction({0, 1, 0}, {0, 0, 0}, {0, 2, 2});
    EXPECT_NEAR(r.x, 0.0, 1e-15);
    EXPECT_NEAR(r.y, std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(r.z, -std::sqrt(0.5), 1e-15);
    // The eye on the point: the normal, not NaN.
    EXPECT_EQ(shading::mirror_direction({0, 1, 0}, {1, 1, 1}, {1, 1, 1}), glm::dvec3(0, 1, 0));
}

// The material bound of the bound criterion (cpu_evaluator.h) against the
// maximum of f_r over the lights a box may hold: its eight corners, the point
// where the mirror ray enters it (when it does) and random points inside, for
// point and directional clusters. The maximum over the box's points is the
// lobe at the largest cosine, which these samples approach from below.
TEST(MaterialBound, IsConservativeOverAMillionRandomConfigurations) {
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto unit = [&] {
        glm::dvec3 v;
        do {
            v = {2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1};
        } while (glm::length(v) < 1e-3 || glm::length(v) > 1.0);
        return glm::normalize(v);
    };
    int checked = 0, glossy_active = 0, hits = 0;
    for (int config = 0; config < 1000000; ++config) {
        const bool directional = config % 4 == 3;
        SurfacePoint p;
        p.position = {4 * u(rng) - 2, 4 * u(rng) - 2, 4 * u(rng) - 2};
        p.normal = unit();
        const glm::dvec3 eye = p.position + (0.1 + 5 * u(rng)) * unit();
        p.mirror = shading::mirror_direction(p.normal, p.position, eye);
        const double roughness = config % 7 == 0 ? 0.1 : 0.1 + 0.9 * u(rng);
        const shading::SurfaceMaterial m =
            surface_material({u(rng), u(rng), u(rng)}, u(rng) < 0.3 ? 1.0 : u(rng), roughness);
        p.albedo = m.diffuse;
        p.specular = m.specular;
        p.exponent = m.exponent;

        // A one-node walk tree: the bound reads its type and box.
        WalkTree one;
        one.nodes.resize(1);
        one.leaves.resize(1);
        GpuTreeNode& node = one.nodes[0];
        node.flags = uint32_t(directional ? LightType::kDirectional : LightType::kPoint) << kNodeTypeShift;
        glm::dvec3 lo, hi;
        if (directional) {
            // A box around a cone of unit directions.
            const glm::dvec3 d = unit();
            const double half = 0.5 * u(rng) * u(rng);
            lo = d - half;
            hi = d + half;
        } else {
            const glm::dvec3 c = p.position + 3.0 * u(rng) * unit();
            const glm::dvec3 half(u(rng), u(rng), u(rng));
            lo = c - half * u(rng);
            hi = c + half * u(rng);
        }
        node.bbox_min = glm::vec3(lo);
        node.bbox_max = glm::vec3(hi);
        lo = glm::dvec3(node.bbox_min);  // the float box is what the bound sees
        hi = glm::dvec3(node.bbox_max);
        const glm::dvec3 bound = material_bound(one, 0, p);

        auto check = [&](const glm::dvec3& y) {
            glm::dvec3 l = directional ? -y : y - p.position;
            const double len = glm::length(l);
            if (!(len > 1e-9)) return;
            const glm::dvec3 f = material_response(p, l / len);
            for (int ch = 0; ch < 3; ++ch) {
                ASSERT_TRUE(std::isfinite(bound[ch]));
                ASSERT_GE(bound[ch] * (1.0 + 1e-6), f[ch])
                    << "config " << config << " channel " << ch << " n " << p.exponent;
            }
            ++checked;
        };
        for (int corner = 0; corner < 8; ++corner)
            check({corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z});
        for (int k = 0; k < 2; ++k)
            check(lo + (hi - lo) * glm::dvec3(u(rng), u(rng), u(rng)));
        // Where the mirror ray enters the box the lobe is at its peak: the
        // bound must reach it (and equal it, since that is the true maximum).
        const glm::dvec3 origin = directional ? glm::dvec3(0.0) : p.position;
        const glm::dvec3 ray = directional ? -p.mirror : p.mirror;
        double t0 = 0.0, t1 = 1e30;
        for (int a = 0; a < 3; ++a) {
            if (std::abs(ray[a]) < 1e-12) {
                if (origin[a] < lo[a] || origin[a] > hi[a]) t0 = 1e31;
                continue;
            }
            double ta = (lo[a] - origin[a]) / ray[a], tb = (hi[a] - origin[a]) / ray[a];
            t0 = std::max(t0, std::min(ta, tb));
            t1 = std::min(t1, std::max(ta, tb));
        }
        if (t0 < t1 && t0 > 1e-6) {
            check(origin + ray * (0.5 * (t0 + t1)));
            ++hits;
            if (p.exponent > 0.0 && p.specular.x > 0.0) {
                const double peak = glossy_lobe(1.0, p.exponent);
                EXPECT_NEAR(bound.x, p.albedo.x / std::numbers::pi + p.specular.x * peak,
                            1e-6 * bound.x);
            }
        }
        if (p.exponent > 0.0) ++glossy_active;
    }
    EXPECT_GT(checked, 9000000);
    EXPECT_GT(glossy_active, 900000);  // nearly every case has a lobe
    EXPECT_GT(hits, 25000);            // and many a mirror ray into the box
}

}  // namespace
}  // namespace lc::client
