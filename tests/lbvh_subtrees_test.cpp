// The LBVH written in parts (mpi/lbvh_units.h, mpi/lbvh_top.h, here in one
// process with no MPI): the parts' subtrees merged and written at the indices
// the top hands out give the one-process result channel, byte for byte, for
// any number of parts, cut anywhere in the sorted keys (also inside a run of
// equal codes, which the ranks' spread never does).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "lightmass_server/builders/cluster_attributes.h"
#include "lightmass_server/mpi/lbvh_top.h"
#include "lightmass_server/mpi/lbvh_units.h"
#include "multi_rank_fixtures.h"
#include "protocol/channel_records.h"

namespace lc::bake {
namespace {

namespace fs = std::filesystem;
using test::scattered_lights;

struct Sorted {
    std::vector<LbvhKey> keys;
    std::vector<uint32_t> groups;
};

// Every light's key in the one-process order: (group, code, input index).
Sorted sorted_keys(const std::vector<SceneLight>& lights) {
    std::vector<glm::dvec3> lo(kLightGroupCount, glm::dvec3(1e300)), hi(kLightGroupCount, glm::dvec3(-1e300));
    for (const SceneLight& light : lights) {
        lo[light_group(light)] = glm::min(lo[light_group(light)], light_point(light));
        hi[light_group(light)] = glm::max(hi[light_group(light)], light_point(light));
    }
    std::vector<std::pair<uint32_t, LbvhKey>> all;
    for (uint32_t i = 0; i < lights.size(); ++i) {
        const size_t g = light_group(lights[i]);
        all.push_back({uint32_t(g), LbvhKey{lbvh_code(lights[i], lbvh_curve(lo[g], hi[g])), i}});
    }
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first < b.first : a.second < b.second;
    });
    Sorted sorted;
    for (const auto& [group, key] : all) {
        sorted.groups.push_back(group);
        sorted.keys.push_back(key);
    }
    return sorted;
}

// Part p: sorted keys [begin, end), with its neighbours' boundary keys.
SortedShare part_of(const Sorted& sorted, const std::vector<SceneLight>& lights, size_t begin, size_t end) {
    SortedShare share;
    share.total_lights = lights.size();
    for (size_t k = begin; k < end; ++k) {
        share.keys.push_back(sorted.keys[k]);
        share.lights.push_back(lights[sorted.keys[k].leaf]);
        ++share.group_begin[sorted.groups[k] + 1];
    }
    for (size_t g = 0; g < kLightGroupCount; ++g) share.group_begin[g + 1] += share.group_begin[g];
    return share;
}

ShareNeighbours neighbours_of(const Sorted& sorted, size_t begin, size_t end) {
    ShareNeighbours near;
    if (begin > 0) near = {true, false, sorted.groups[begin - 1], 0, sorted.keys[begin - 1].code, 0};
    if (end < sorted.keys.size()) {
        near.has_after = true;
        near.after_group = sorted.groups[end];
        near.after_code = sorted.keys[end].code;
    }
    return near;
}

// The tree written by `parts` parts into a file, read back.
std::vector<uint8_t> written_in_parts(const std::vector<SceneLight>& lights, uint32_t parts,
                                      const BuildOptions& options, const fs::path& file) {
    const Sorted sorted = sorted_keys(lights);
    std::vector<SortedShare> shares;
    std::vector<std::vector<LbvhUnit>> units;
    std::vector<UnitSummary> summaries;
    std::vector<uint32_t> depths;
    for (uint32_t p = 0; p < parts; ++p) {
        const size_t begin = lights.size() * p / parts, end = lights.size() * (p + 1) / parts;
        shares.push_back(part_of(sorted, lights, begin, end));
        Result<std::vector<LbvhUnit>> merged =
            merge_units(shares.back(), neighbours_of(sorted, begin, end), 64, options);
        EXPECT_TRUE(merged.ok()) << (merged ? "" : merged.error());
        units.push_back(merged ? std::move(merged.value()) : std::vector<LbvhUnit>{});
        for (const LbvhUnit& unit : units.back()) {
            summaries.push_back(summarize_unit(shares.back(), unit));
            depths.insert(depths.end(), unit.level_counts.begin(), unit.level_counts.end());
        }
    }
    Result<LbvhTop> top = build_lbvh_top(summaries, depths, options);
    EXPECT_TRUE(top.ok()) << (top ? "" : top.error());
    if (!top) return {};
    std::FILE* out = std::fopen(file.c_str(), "wb");
    const std::vector<uint8_t> prefix = encode_result_prefix(top->node_count);
    std::fwrite(prefix.data(), 1, prefix.size(), out);
    std::fclose(out);
    fs::resize_file(file, prefix.size() + uint64_t(top->node_count) * result_record_bytes());
    std::FILE* records = std::fopen(file.c_str(), "r+b");
    std::vector<int32_t> representatives;
    size_t at = 0;
    for (uint32_t p = 0; p < parts; ++p) {
        for (const LbvhUnit& unit : units[p]) {
            const std::span<const uint32_t> bases(top->bases.data() + top->base_at[at],
                                                  unit.level_counts.size());
            Result<int32_t> representative = write_unit_records(fileno(records), shares[p], unit, bases);
            EXPECT_TRUE(representative.ok()) << (representative ? "" : representative.error());
            representatives.push_back(representative ? *representative : -1);
            ++at;
        }
    }
    EXPECT_TRUE(write_top_records(fileno(records), *top, representatives).ok());
    std::fclose(records);
    std::ifstream in(file, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

TEST(LbvhSubtrees, WrittenInPartsTheyGiveTheOneProcessFile) {
    std::vector<SceneLight> lights = scattered_lights(5000);
    for (size_t i = 0; i < 600; ++i) lights[i].position = glm::vec3(3.0f);  // one code over part boundaries
    BuildOptions options;
    options.builder = BuilderKind::kLbvh;
    options.seed = 3;
    Result<BuildResult> whole = build_light_tree(lights, options, {});
    ASSERT_TRUE(whole.ok());
    const std::vector<uint8_t> expected = encode_result_channel(whole->tree);
    const fs::path file = fs::temp_directory_path() / ("lbvh_subtrees_test_" + std::to_string(getpid()));
    for (uint32_t parts : {1u, 2u, 3u, 4u, 7u, 64u}) {
        EXPECT_EQ(written_in_parts(lights, parts, options, file), expected) << parts << " parts";
    }
    fs::remove(file);
}

}  // namespace
}  // namespace lc::bake
