// Environment sampling plus tree build for 10^4, 10^5 and 10^6 directional
// lights, from a Preetham sun and sky and from a 2048 x 1024 HDR map. Prints
// CSV (scripts/bench/environment.sh writes it to docs/bench/environment_sampling.csv).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "lightcuts/seeded_mixer.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/builders/tree_builder.h"

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// A synthetic HDRI: a dim sky gradient, a bright sun-like spot, noise.
lc::Environment synthetic_map() {
    lc::Environment environment;
    environment.map = lc::EquirectMap{2048, 1024, {}};
    environment.map.texels.reserve(2048 * 1024);
    lc::SplitMix64 random(1);
    for (uint32_t y = 0; y < 1024; ++y) {
        for (uint32_t x = 0; x < 2048; ++x) {
            const float sky = y < 512 ? 0.5f + 0.5f * float(512 - y) / 512.0f : 0.1f;
            const bool spot = (x - 600u) * (x - 600u) + (y - 200u) * (y - 200u) < 100u;
            const float noise = 0.2f * float(random.uniform());
            environment.map.texels.push_back(spot ? glm::vec3(5000.0f) : glm::vec3(sky * 0.6f + noise, sky * 0.8f, sky));
        }
    }
    return environment;
}

}  // namespace

int main(int argc, char** argv) {
    const uint32_t largest = argc > 1 ? uint32_t(std::atoi(argv[1])) : 1000000u;
    lc::Environment sky;
    sky.sky = lc::SkyParameters{30.0f, 40.0f, 3.0f};
    const lc::Environment map = synthetic_map();
    std::printf("source,lights,builder,sample_ms,build_ms,nodes\n");
    for (uint32_t count = 10000; count <= largest; count *= 10) {
        for (const auto& [name, environment] : {std::pair<std::string, const lc::Environment*>{"sky", &sky},
                                                {"hdr_2048x1024", &map}}) {
            for (lc::BuilderKind builder : {lc::BuilderKind::kAgglomerative, lc::BuilderKind::kLbvh}) {
                // The paper's agglomerative builder takes minutes at 10^6 on two cores: LBVH only there.
                if (builder == lc::BuilderKind::kAgglomerative && count > 100000) continue;
                auto start = std::chrono::steady_clock::now();
                auto sampled = lc::bake::sample_environment(*environment, count, 7);
                const double sample_ms = ms_since(start);
                if (!sampled) return std::fprintf(stderr, "%s\n", sampled.error().c_str()), 1;
                lc::bake::BuildOptions options;
                options.builder = builder;
                start = std::chrono::steady_clock::now();
                auto built = lc::bake::build_light_tree(sampled->lights, options, {});
                const double build_ms = ms_since(start);
                if (!built) return std::fprintf(stderr, "%s\n", built.error().c_str()), 1;
                std::printf("%s,%u,%s,%.1f,%.1f,%zu\n", name.c_str(), count, lc::builder_name(builder), sample_ms,
                            build_ms, built->tree.nodes.size());
                std::fflush(stdout);
            }
        }
    }
    return 0;
}
