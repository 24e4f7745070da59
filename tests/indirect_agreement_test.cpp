// The two indirect solvers against each other and against a brute-force
// path-traced reference, on a Cornell box lit by its ceiling panel: every
// wall's mean reflected radiosity, and the red wall's colour on its neighbour.
#include <gtest/gtest.h>

#include <cstdio>

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
