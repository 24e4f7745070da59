// The point-to-polygon form factor: a closed formula for a rectangle, the
// horizon clip, and closed enclosures whose form factors must sum to one.
#include "lightmass_server/indirect/point_polygon_form_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "indirect_scenes.h"
#include "lightmass_server/indirect/patch_mesh.h"

namespace lc::bake {
namespace {

// dA to a parallel a x b rectangle at height c with a corner above dA
// (Howell's catalogue, configuration B-3).
double corner_rectangle(double a, double b, double c) {
    double A = a / c, B = b / c;
    double sa = std::sqrt(1.0 + A * A), sb = std::sqrt(1.0 + B * B);
    return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * std::numbers::pi);
}

double rectangle(glm::dvec3 x, glm::dvec3 n, glm::dvec3 o, glm::dvec3 u, glm::dvec3 v) {
    glm::dvec3 t0[3] = {o, o + u, o + u + v};
    glm::dvec3 t1[3] = {o, o + u + v, o + v};
    return point_triangle_form_factor(x, n, t0) + point_triangle_form_factor(x, n, t1);
}

TEST(PointPolygonFormFactor, MatchesTheClosedFormForAParallelRectangle) {
    for (double c : {0.25, 1.0, 3.0}) {
        double f = rectangle({0, 0, 0}, {0, 0, 1}, {0, 0, c}, {2.0, 0, 0}, {0, 1.5, 0});
        EXPECT_NEAR(f, corner_rectangle(2.0, 1.5, c), 1e-12) << "height " << c;
    }
}

TEST(PointPolygonFormFactor, SeesOnlyWhatLiesAboveItsHorizon) {
    // A rectangle straddling the tangent plane counts its upper half only.
    double whole = rectangle({0, 0, 0}, {0, 0, 1}, {1, -1, 0}, {0, 2, 0}, {0, 0, 1});
    double half = rectangle({0, 0, 0}, {0, 0, 1}, {1, -1, -1}, {0, 2, 0}, {0, 0, 2});
    EXPECT_NEAR(half, whole, 1e-12);
    // Entirely below: nothing.
    EXPECT_EQ(rectangle({0, 0, 0}, {0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}), 0.0);
}

TEST(PointPolygonFormFactor, AClosedEnclosureSumsToOne) {
    SceneGeometry box = test::closed_box({}, 2.0f);
    auto mesh = make_patches(box, 0.5f, 1 << 16);
    ASSERT_TRUE(mesh.ok()) << mesh.error();
    const std::vector<Patch>& patches = mesh->patches;
    double worst = 0.0;
    for (size_t j = 0; j < patches.size(); ++j) {
        double sum = 0.0;
        for (size_t i = 0; i < patches.size(); ++i) {
            if (i == j) continue;
            glm::dvec3 corners[3] = {glm::dvec3(patches[i].vertices[0]), glm::dvec3(patches[i].vertices[1]),
                                     glm::dvec3(patches[i].vertices[2])};
            sum += point_triangle_form_factor(glm::dvec3(patches[j].centre), glm::dvec3(patches[j].normal), corners);
        }
        worst = std::max(worst, std::abs(sum - 1.0));
    }
    EXPECT_LT(worst, 0.01) << patches.size() << " patches";
}

TEST(PatchMesh, SplitsTrianglesIntoEqualPatchesAndSkipsDegenerateOnes) {
    SceneGeometry g = test::closed_box({}, 1.0f);
    g.triangles.push_back(test::flat_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0));
    g.triangles.back().positions[2] = {2, 0, 0};  // collinear: no area
    auto mesh = make_patches(g, 0.5f, 1 << 16);
    ASSERT_TRUE(mesh.ok()) << mesh.error();
    EXPECT_EQ(mesh->skipped_degenerate, 1u);
    // Edges up to sqrt(2): k = 3, nine patches per triangle.
    ASSERT_EQ(mesh->patches.size(), 12u * 9u);
    double area = 0.0;
    for (const Patch& p : mesh->patches) {
        EXPECT_NEAR(p.area, 0.5f / 9.0f, 1e-6f);
        area += p.area;
    }
    EXPECT_NEAR(area, 6.0, 1e-5);
    auto too_many = make_patches(g, 1e-3f, 1000);
    ASSERT_FALSE(too_many.ok());
    EXPECT_NE(too_many.error().find("patch"), std::string::npos);
    EXPECT_FALSE(make_patches(g, 0.0f, 1000).ok());
}

// Two million patches take hundreds of milliseconds: a cancel stops the
// split, polled per row of a triangle's grid; a live stop changes nothing.
TEST(PatchMesh, ACancelStopsTheSplitAndALiveStopChangesNothing) {
    const SceneGeometry g = test::closed_box({}, 1.0f);
    bake::BakeStop live;
    auto with_stop = make_patches(g, 0.01f, 1 << 22, &live);
    auto without = make_patches(g, 0.01f, 1 << 22);
    ASSERT_TRUE(with_stop.ok() && without.ok());
    ASSERT_EQ(with_stop->patches.size(), without->patches.size());
    EXPECT_GT(without->patches.size(), 100000u);
    for (size_t i = 0; i < without->patches.size(); i += 997) {
        EXPECT_EQ(with_stop->patches[i].centre, without->patches[i].centre);
    }
    bake::BakeStop cancelled;
    cancelled.cancel();
    auto stopped = make_patches(g, 0.01f, 1 << 22, &cancelled);
    ASSERT_FALSE(stopped.ok());
    EXPECT_EQ(stopped.error_kind(), ErrorKind::kCancelled) << stopped.error();
}

}  // namespace
}  // namespace lc::bake
