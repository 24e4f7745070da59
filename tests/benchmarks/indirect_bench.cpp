// Indirect light on the Cornell box lit by its ceiling panel: bake time and
// error against a path-traced reference for VPL counts and radiosity patch
// sizes, and the radiosity convergence curve. Writes two CSVs (the paths are
// the arguments); scripts/bench/indirect.sh runs it and plots them.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "lightmass_server/indirect/radiosity_solver.h"
#include "lightmass_server/indirect/vpl_tracer.h"
#include "tests/indirect_scenes.h"

namespace {

using lc::bake::IndirectLight;

// The largest relative difference over the walls' mean reflected radiosity
// (all three channels), and the mean of those differences.
struct WallError {
    double max = 0.0;
    double mean = 0.0;
};

WallError wall_error(const std::vector<glm::dvec3>& estimate, const std::vector<glm::dvec3>& reference) {
    WallError e;
    int n = 0;
    for (size_t w = 0; w < reference.size(); ++w) {
        for (int c = 0; c < 3; ++c) {
            double d = std::abs(estimate[w][c] / reference[w][c] - 1.0);
            e.max = std::max(e.max, d);
            e.mean += d;
            ++n;
        }
    }
    e.mean /= n;
    return e;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s RESULTS.csv CONVERGENCE.csv\n", argv[0]);
        return 2;
    }
    lc::test::CornellBox box = lc::test::cornell_box();
    auto caster = lc::RayCaster::build(box.geometry, 0);
    if (!caster.ok()) {
        std::fprintf(stderr, "ray caster: %s\n", caster.error().c_str());
        return 1;
    }
    auto start = std::chrono::steady_clock::now();
    std::vector<glm::dvec3> reference = lc::test::path_traced_wall_means(box, *caster, 1000000, 99);
    std::fprintf(stderr, "path-traced reference: %.1f s\n", seconds_since(start));

    FILE* results = std::fopen(argv[1], "w");
    FILE* convergence = std::fopen(argv[2], "w");
    if (!results || !convergence) {
        std::fprintf(stderr, "cannot write the CSVs\n");
        return 1;
    }
    std::fprintf(results, "method,parameter,lights,bake_s,max_wall_error,mean_wall_error\n");
    for (uint64_t count : {1000ull, 10000ull, 100000ull, 1000000ull}) {
        lc::bake::VplOptions options;
        options.particle_count = count;
        options.bounces = 64;
        options.seed = 1;
        start = std::chrono::steady_clock::now();
        auto r = lc::bake::trace_vpls(box.geometry, *caster, {}, options, {});
        double bake_s = seconds_since(start);
        if (!r.ok()) return 1;
        WallError e = wall_error(lc::test::wall_means(box, r->lights, *caster), reference);
        std::fprintf(results, "vpl,%llu,%zu,%.4f,%.5f,%.5f\n", static_cast<unsigned long long>(count),
                     r->lights.size(), bake_s, e.max, e.mean);
        std::fflush(results);
    }
    std::fprintf(convergence, "patch_size,step,seconds,shot_fraction\n");
    for (float size : {0.5f, 0.25f, 0.125f}) {
        lc::bake::RadiosityOptions options;
        options.patch_size = size;
        options.tolerance = 1e-3;
        start = std::chrono::steady_clock::now();
        auto r = lc::bake::solve_radiosity(box.geometry, *caster, {}, options, {});
        double bake_s = seconds_since(start);
        if (!r.ok()) return 1;
        WallError e = wall_error(lc::test::wall_means(box, r->lights, *caster), reference);
        std::fprintf(results, "radiosity,%g,%zu,%.4f,%.5f,%.5f\n", size, r->lights.size(), bake_s, e.max, e.mean);
        std::fflush(results);
        for (const lc::bake::ConvergencePoint& p : r->convergence) {
            std::fprintf(convergence, "%g,%llu,%.5f,%.6f\n", size, static_cast<unsigned long long>(p.step),
                         p.seconds, p.shot_fraction);
        }
    }
    std::fclose(results);
    std::fclose(convergence);
    return 0;
}
