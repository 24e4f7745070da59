// Radiosity split over parts (radiosity_parts.h) without MPI: each part runs
// on a thread of its own and the all-gather is a barrier over shared slots.
// The parts' lights, concatenated in part order, are the one-process lights
// byte for byte at 1 to 4 parts, and each part shoots into its blocks only.
#include <gtest/gtest.h>

#include <barrier>
#include <cstring>
#include <thread>

#include "indirect_scenes.h"
#include "lightmass_server/indirect/radiosity_parts.h"
#include "lightmass_server/indirect/radiosity_solver.h"

namespace lc::bake {
namespace {

// An all-gather between threads: every part writes its slot, all wait, all
// read every slot, all wait again (so no slot changes while it is read).
class ThreadAllGather {
public:
    explicit ThreadAllGather(uint32_t parts) : barrier_(parts), slots_(parts) {}
    size_t parts() const { return slots_.size(); }

    std::vector<double> operator()(uint32_t part, const std::vector<double>& mine) {
        slots_[part] = mine;
        barrier_.arrive_and_wait();
        std::vector<double> all;
        for (const std::vector<double>& slot : slots_) all.insert(all.end(), slot.begin(), slot.end());
        barrier_.arrive_and_wait();
        return all;
    }
    // A part that finished stops counting: a part that shot more often than
    // another then reads a stale slot and the test fails instead of hanging.
    void leave() { barrier_.arrive_and_drop(); }

private:
    std::barrier<> barrier_;
    std::vector<std::vector<double>> slots_;
};

RadiosityOptions cornell_options() {
    RadiosityOptions options;
    options.patch_size = 0.08f;  // about 3,600 patches: 15 blocks, several for every part
    options.tolerance = 0.25;    // a few hundred shots, every part's patches among the shooters
    options.visibility_samples = 1;
    return options;
}

std::vector<SceneLight> two_lights() {
    std::vector<SceneLight> lights(2);
    lights[0].position = glm::vec3(0.3f, 0.9f, 0.4f);
    lights[0].intensity = 2.0f;
    lights[1].position = glm::vec3(0.7f, 0.5f, 0.6f);
    lights[1].color = glm::vec3(1.0f, 0.5f, 0.25f);
    return lights;
}

std::vector<uint8_t> bytes_of(const std::vector<IndirectLight>& lights) {
    std::vector<uint8_t> bytes(lights.size() * sizeof(IndirectLight));
    if (!lights.empty()) std::memcpy(bytes.data(), lights.data(), bytes.size());
    return bytes;
}

struct PartsSolve {
    std::vector<IndirectLight> lights;  // every part's, in part order
    std::vector<RadiosityResult> results;
};

PartsSolve solve_in_parts(const SceneGeometry& geometry, const RayCaster& caster, uint32_t parts) {
    ThreadAllGather gather(parts);
    std::vector<Result<RadiosityResult>> results(parts, make_error("not run"));
    std::vector<std::thread> threads;
    for (uint32_t part = 0; part < parts; ++part) {
        threads.emplace_back([&, part] {
            const RadiosityParts share{
                part, parts, [&gather, part](const std::vector<double>& mine, const std::vector<int>& sizes) {
                    EXPECT_EQ(sizes.size(), gather.parts());
                    EXPECT_EQ(size_t(sizes[part]), mine.size())
                        << "part " << part << "'s size is not its summary's";
                    return Result<std::vector<double>>(gather(part, mine));
                }};
            RadiosityOptions options = cornell_options();
            options.parts = &share;
            results[part] = solve_radiosity(geometry, caster, two_lights(), options, {});
            gather.leave();
        });
    }
    for (std::thread& thread : threads) thread.join();
    PartsSolve solve;
    for (Result<RadiosityResult>& result : results) {
        EXPECT_TRUE(result.ok()) << (result ? "" : result.error());
        if (!result) continue;
        solve.lights.insert(solve.lights.end(), result->lights.begin(), result->lights.end());
        solve.results.push_back(std::move(result.value()));
    }
    return solve;
}

TEST(RadiosityParts, TheReceiversOfThePartsCoverEveryPatchOnceInOrder) {
    for (uint64_t patches : {0ull, 1ull, 255ull, 256ull, 257ull, 4000ull}) {
        for (uint32_t parts : {1u, 2u, 3u, 4u, 7u}) {
            uint64_t next = 0;
            for (uint32_t part = 0; part < parts; ++part) {
                const IndexRange mine = radiosity_receivers_of(patches, part, parts);
                EXPECT_EQ(mine.begin, next) << patches << " patches, part " << part << " of " << parts;
                EXPECT_LE(mine.begin, mine.end);
                if (mine.begin != mine.end) {
                    EXPECT_EQ(mine.begin % kRadiosityBlockPatches, 0u);
                }
                next = mine.end;
            }
            EXPECT_EQ(next, patches) << patches << " patches over " << parts << " parts";
        }
    }
}

TEST(RadiosityParts, ThePartsLightsAreTheOneProcessLightsAtOneToFourParts) {
    const test::CornellBox box = test::cornell_box();
    Result<RayCaster> caster = RayCaster::build(box.geometry, 1);
    ASSERT_TRUE(caster.ok()) << caster.error();
    Result<RadiosityResult> whole =
        solve_radiosity(box.geometry, *caster, two_lights(), cornell_options(), {});
    ASSERT_TRUE(whole.ok()) << whole.error();
    const size_t patches = whole->mesh.patches.size();
    ASSERT_GT(radiosity_block_count(patches), 8u) << "too few blocks to give every part some";
    ASSERT_GT(whole->steps, 10u);
    ASSERT_FALSE(whole->lights.empty());
    for (uint32_t parts : {1u, 2u, 3u, 4u}) {
        const PartsSolve split = solve_in_parts(box.geometry, *caster, parts);
        ASSERT_EQ(split.results.size(), parts);
        EXPECT_EQ(bytes_of(split.lights), bytes_of(whole->lights)) << parts << " parts";
        for (uint32_t part = 0; part < parts; ++part) {
            const RadiosityResult& r = split.results[part];
            EXPECT_EQ(r.steps, whole->steps) << "part " << part << " of " << parts;
            EXPECT_EQ(r.unshot_fraction, whole->unshot_fraction) << "part " << part << " of " << parts;
            // Each part's lights sit on its own receivers: it shot into those alone.
            const IndexRange mine = radiosity_receivers_of(patches, part, parts);
            EXPECT_FALSE(r.lights.empty()) << "part " << part << " of " << parts << " made no light";
            for (size_t j = 0; j < patches; ++j) {
                if (mine.contains(j)) continue;
                ASSERT_EQ(r.radiosity[j], glm::vec3(0.0f)) << "part " << part << " wrote patch " << j;
            }
        }
    }
}

}  // namespace
}  // namespace lc::bake
