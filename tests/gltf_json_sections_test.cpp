// The one-pass scan that splits a glTF's JSON into the node reader's runs of
// elements and the remainder for tinygltf (gltf_json_sections.h): runs hold
// whole elements whatever their size, strings and escapes never end an
// element early, and every document it cannot split so is refused.
#include "editor_client/scene/gltf/gltf_json_sections.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lc::client {
namespace {

struct Split {
    std::optional<std::string> remainder;
    std::vector<std::pair<GltfSection, std::string>> runs;
    std::vector<size_t> consumed;
};

Split split(std::string_view json, size_t run_bytes) {
    Split out;
    out.remainder = split_gltf_sections(json, run_bytes,
                                        {[&](GltfSection section, std::string_view elements) {
                                             out.runs.emplace_back(section, std::string(elements));
                                             return true;
                                         },
                                         [&](size_t offset) { out.consumed.push_back(offset); }});
    return out;
}

const std::string kDocument = R"({
  "asset": {"version": "2.0", "generator": "a \"quoted\" ] } , name"},
  "scenes": [ {"nodes": [0, 1]} ],
  "nodes": [
    {"name": "odd \\\" ] }, [ {", "children": [1]},
    {"translation": [1, -2e3, 0.5], "extras": {"k": [[], {}]}},
    {"name": "\\\\"}
  ],
  "extensions": {"EXT_other": {"lights": [1]}, "KHR_lights_punctual": {"lights": [{"type": "point"}, {"type": "spot", "spot": {}}]}},
  "buffers": []
}
)";

TEST(GltfJsonSections, SplitsTheThreeArraysAndKeepsTheRest) {
    const Split whole = split(kDocument, size_t{1} << 20);
    ASSERT_TRUE(whole.remainder.has_value());
    EXPECT_EQ(*whole.remainder, R"({
  "asset": {"version": "2.0", "generator": "a \"quoted\" ] } , name"},
  "scenes": [],
  "nodes": [],
  "extensions": {"EXT_other": {"lights": [1]}, "KHR_lights_punctual": {"lights": []}},
  "buffers": []
}
)");
    ASSERT_EQ(whole.runs.size(), 3u);
    EXPECT_EQ(whole.runs[0].first, GltfSection::kScenes);
    EXPECT_EQ(whole.runs[0].second, R"({"nodes": [0, 1]})");
    EXPECT_EQ(whole.runs[1].first, GltfSection::kNodes);
    EXPECT_EQ(whole.runs[1].second, R"({"name": "odd \\\" ] }, [ {", "children": [1]},
    {"translation": [1, -2e3, 0.5], "extras": {"k": [[], {}]}},
    {"name": "\\\\"})");
    EXPECT_EQ(whole.runs[2].first, GltfSection::kLights);
    EXPECT_EQ(whole.runs[2].second, R"({"type": "point"}, {"type": "spot", "spot": {}})");
}

// Runs of one byte: one element each, the text behind each released in order.
TEST(GltfJsonSections, SmallRunsHoldOneWholeElementEach) {
    const Split runs = split(kDocument, 1);
    ASSERT_TRUE(runs.remainder.has_value());
    EXPECT_EQ(*runs.remainder, *split(kDocument, size_t{1} << 20).remainder);
    std::vector<std::string> nodes;
    for (const auto& [section, text] : runs.runs)
        if (section == GltfSection::kNodes) nodes.push_back(text);
    ASSERT_EQ(nodes.size(), 3u);
    EXPECT_EQ(nodes[2], R"({"name": "\\\\"})");
    ASSERT_EQ(runs.consumed.size(), runs.runs.size());
    for (size_t i = 0; i < runs.consumed.size(); ++i) {
        EXPECT_LE(runs.consumed[i], kDocument.size());
        if (i > 0) {
            EXPECT_GT(runs.consumed[i], runs.consumed[i - 1]);
        }
        // The run ends where the released text ends.
        EXPECT_EQ(kDocument.substr(runs.consumed[i] - runs.runs[i].second.size(), runs.runs[i].second.size()),
                  runs.runs[i].second);
    }
}

TEST(GltfJsonSections, EmptyAndAbsentSectionsGiveNoRuns) {
    const Split empty = split(R"({"nodes": [ ], "asset": {}})", 64);
    ASSERT_TRUE(empty.remainder.has_value());
    EXPECT_EQ(*empty.remainder, R"({"nodes": [], "asset": {}})");
    EXPECT_TRUE(empty.runs.empty());
    const Split none = split(" {} ", 64);
    ASSERT_TRUE(none.remainder.has_value());
    EXPECT_EQ(*none.remainder, " {} ");
}

TEST(GltfJsonSections, RefusesWhatItCannotSplit) {
    const std::vector<std::string> refused = {
        "",
        "[]",
        R"({"nodes": [{}]} x)",
        R"({"nodes": [{}], "nodes": []})",
        R"({"nodes": {}})",
        R"({"nodes": [{},]})",
        R"({"nodes": [,{}]})",
        R"({"nodes": [{} {}]})",
        R"({"nodes": [{"a": "unterminated]})",
        R"({"nodes": [{"a": [1}]})",
        R"({"n\u006fdes": []})",
        R"({"asset" {}})",
        R"({"asset": {}, })",
        R"({"asset": })",
        R"({"extensions": {"KHR_lights_punctual": {"lights": [{}], "lights": []}}})",
        R"({"extensions": {"KHR_lights_punctual": {}, "KHR_lights_punctual": {}}})",
        R"({"extensions": {}, "extensions": {}})",
        R"({"extensions": []})",
    };
    for (const std::string& json : refused) {
        EXPECT_FALSE(split(json, 64).remainder.has_value()) << json;
    }
    // A run the handler refuses stops the scan.
    const auto refuse = split_gltf_sections(R"({"nodes": [{}]})", 64,
                                            {[](GltfSection, std::string_view) { return false; }, {}});
    EXPECT_FALSE(refuse.has_value());
}

}  // namespace
}  // namespace lc::client
