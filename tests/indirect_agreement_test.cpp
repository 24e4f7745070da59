// The two indirect solvers against each other and against a brute-force
// path-traced reference, on a Cornell box lit by its ceiling panel: every
// wall's mean reflected radiosity, and the red wall's colour on its neighbour.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "indirect_scenes.h"
#include "lightmass_server/indirect/radiosity_solver.h"
#include "lightmass_server/indirect/vpl_tracer.h"

namespace lc::bake {
namespace {

const char* const kWallNames[] = {"floor", "ceiling", "back", "red", "green"};

class CornellAgreement : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        box_ = new test::CornellBox(test::cornell_box());
        auto caster = RayCaster::build(box_->geometry, 0);
        ASSERT_TRUE(caster.ok());
        caster_ = new RayCaster(std::move(caster).value());
    }
    static void TearDownTestSuite() {
        delete caster_;
        delete box_;
    }

    static std::vector<IndirectLight> vpls(uint32_t bounces) {
        VplOptions options;
        options.particle_count = 100000;
        options.bounces = bounces;
        options.seed = 11;
        auto r = trace_vpls(box_->geometry, *caster_, {}, options, {});
        EXPECT_TRUE(r.ok());
        return r.ok() ? r->lights : std::vector<IndirectLight>{};
    }

    static test::CornellBox* box_;
    static RayCaster* caster_;
};
test::CornellBox* CornellAgreement::box_ = nullptr;
RayCaster* CornellAgreement::caster_ = nullptr;

void expect_close(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b, double tolerance,
                  const char* what) {
    for (int w = 0; w < test::kWallCount; ++w) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(a[w][c] / b[w][c], 1.0, tolerance) << what << ", " << kWallNames[w] << " channel " << c;
        }
    }
}

TEST_F(CornellAgreement, VplsRadiosityAndPathTracingAgreeOnEveryWall) {
    std::vector<glm::dvec3> vpl = test::wall_means(*box_, vpls(64), *caster_);

    RadiosityOptions options;
    options.patch_size = 0.25f;
    options.tolerance = 1e-3;
    auto radiosity = solve_radiosity(box_->geometry, *caster_, {}, options, {});
    ASSERT_TRUE(radiosity.ok()) << radiosity.error();
    ASSERT_TRUE(radiosity->converged) << radiosity->message;
    std::vector<glm::dvec3> patches = test::wall_means(*box_, radiosity->lights, *caster_);

    std::vector<glm::dvec3> reference = test::path_traced_wall_means(*box_, *caster_, 40000, 5);
    for (int w = 0; w < test::kWallCount; ++w) {
        std::printf("%-8s vpl %.4f %.4f %.4f  radiosity %.4f %.4f %.4f  path traced %.4f %.4f %.4f\n",
                    kWallNames[w], vpl[w].x, vpl[w].y, vpl[w].z, patches[w].x, patches[w].y, patches[w].z,
                    reference[w].x, reference[w].y, reference[w].z);
    }
    expect_close(vpl, patches, 0.05, "vpl against radiosity");
    expect_close(vpl, reference, 0.05, "vpl against the path-traced reference");
    expect_close(patches, reference, 0.05, "radiosity against the path-traced reference");
}

// At their defaults (VPL paths followed until Russian roulette ends them,
// radiosity to 1% unshot) the two solvers bounce the same light, and it is
// the path tracer's; the same seed gives the same VPLs.
TEST_F(CornellAgreement, VplAndRadiosityAgreeAtTheirDefaults) {
    VplOptions defaults;
    defaults.seed = 11;
    auto traced = trace_vpls(box_->geometry, *caster_, {}, defaults, {});
    ASSERT_TRUE(traced.ok()) << traced.error();
    uint32_t deepest = 0;
    for (const IndirectLight& l : traced->lights) deepest = std::max(deepest, l.bounce);
    EXPECT_GT(deepest, 8u);  // no one-bounce default
    EXPECT_LT(traced->lights.size(), 10u * defaults.particle_count);
    auto again = trace_vpls(box_->geometry, *caster_, {}, defaults, {});
    ASSERT_TRUE(again.ok());
    ASSERT_EQ(again->lights.size(), traced->lights.size());
    EXPECT_EQ(std::memcmp(again->lights.data(), traced->lights.data(),
                          traced->lights.size() * sizeof(IndirectLight)),
              0);

    auto radiosity = solve_radiosity(box_->geometry, *caster_, {}, RadiosityOptions{}, {});
    ASSERT_TRUE(radiosity.ok()) << radiosity.error();
    std::vector<glm::dvec3> vpl = test::wall_means(*box_, traced->lights, *caster_);
    std::vector<glm::dvec3> patches = test::wall_means(*box_, radiosity->lights, *caster_);
    std::vector<glm::dvec3> reference = test::path_traced_wall_means(*box_, *caster_, 40000, 5);
    for (int w = 0; w < test::kWallCount; ++w) {
        std::printf("defaults: %-8s vpl %.4f radiosity %.4f path traced %.4f (green channel), %u VPL bounces\n",
                    kWallNames[w], vpl[w].y, patches[w].y, reference[w].y, deepest);
    }
    expect_close(vpl, patches, 0.05, "default vpl against default radiosity");
    expect_close(vpl, reference, 0.05, "default vpl against the path-traced reference");
    expect_close(patches, reference, 0.05, "default radiosity against the path-traced reference");
}

// On the back wall's half next to the red wall: one bounce (the panel's
// direct light reflected) is as white as the panel; more bounces carry red.
TEST_F(CornellAgreement, TheRedWallBleedsOntoItsWhiteNeighbour) {
    auto red_over_green = [&](const std::vector<IndirectLight>& lights) {
        glm::dvec3 sum(0.0);
        for (const IndirectLight& l : lights) {
            bool on_back_wall = l.normal.z > 0.99f && l.position.z < 1e-3f;
            if (on_back_wall && l.position.x < 0.5f) sum += glm::dvec3(l.power);
        }
        return sum.x / sum.y;
    };
    EXPECT_NEAR(red_over_green(vpls(1)), 1.0, 1e-6);
    double bled = red_over_green(vpls(8));
    EXPECT_GT(bled, 1.05);

    RadiosityOptions options;
    options.patch_size = 0.25f;
    auto radiosity = solve_radiosity(box_->geometry, *caster_, {}, options, {});
    ASSERT_TRUE(radiosity.ok());
    EXPECT_GT(red_over_green(radiosity->lights), 1.05);
    std::printf("back wall by the red wall, red/green: vpl %.3f, radiosity %.3f\n", bled,
                red_over_green(radiosity->lights));
}

}  // namespace
}  // namespace lc::bake
