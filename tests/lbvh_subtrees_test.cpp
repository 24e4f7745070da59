// The LBVH's subtrees merged elsewhere (lbvh_builder.h's LbvhRemoteMerges and
// merge_lbvh_subtree, here in one process): the same tree for any number of parts.
#include <gtest/gtest.h>

#include "lightmass_server/lbvh_builder.h"
#include "multi_rank_fixtures.h"
#include "protocol/channel_records.h"

namespace lc::bake {
namespace {

using test::scattered_lights;

// The LBVH with its subtrees merged "elsewhere" (merge_lbvh_subtree, in this
// process): the same tree as built whole, for any number of parts.
TEST(LbvhSubtrees, MergedElsewhereTheyGiveTheSameTree) {
    const std::vector<SceneLight> lights = scattered_lights(5000);
    BuildOptions options;
    options.builder = BuilderKind::kLbvh;
    options.seed = 3;
    Result<BuildResult> whole = build_light_tree(lights, options, {});
    ASSERT_TRUE(whole.ok());
    for (uint32_t parts : {2u, 3u, 4u, 7u}) {
        std::vector<std::vector<std::vector<LbvhKey>>> sent(parts);
        size_t subtrees_sent = 0;
        LbvhRemoteMerges remote;
        remote.parts = parts;
        remote.send = [&](uint32_t part, const std::vector<std::span<const LbvhKey>>& subtrees) -> Status {
            sent[part].clear();
            for (const auto& s : subtrees) sent[part].emplace_back(s.begin(), s.end());
            subtrees_sent += subtrees.size();
            return Ok{};
        };
        remote.receive = [&](uint32_t part) -> Result<std::vector<std::vector<BuildNode>>> {
            std::vector<std::vector<BuildNode>> merged;
            for (const std::vector<LbvhKey>& keys : sent[part]) {
                std::vector<SceneLight> their_lights;
                for (const LbvhKey& key : keys) their_lights.push_back(lights[key.leaf]);
                Result<std::vector<BuildNode>> nodes = merge_lbvh_subtree(keys, their_lights, options);
                if (!nodes) return nodes.failure();
                merged.push_back(std::move(nodes.value()));
            }
            return merged;
        };
        BuildOptions split = options;
        split.lbvh_remote = &remote;
        Result<BuildResult> built = build_light_tree(lights, split, {});
        ASSERT_TRUE(built.ok()) << built.error();
        EXPECT_GT(subtrees_sent, 0u) << parts << " parts";
        EXPECT_EQ(encode_result_channel(built->tree), encode_result_channel(whole->tree))
            << parts << " parts";
    }
}

}  // namespace
}  // namespace lc::bake
