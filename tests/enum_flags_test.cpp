// The name tables (lightcuts/name_table.h) and the flags that parse through
// them (commands/enum_flags.h, commands/shared_render_flags.h): each name is
// written once and read both ways; a wrong name is refused with the names.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "editor_client/commands/enum_flags.h"
#include "editor_client/commands/shared_render_flags.h"
#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/supersampled_render.h"
#include "lightcuts/device/limits.h"
#include "lightcuts/occlusion/shadow_ray.h"

namespace lc::client {
namespace {

// Every name leads to its value and back, no name or value twice.
template <typename Enum, size_t N>
void expect_round_trip(const NameTable<Enum, N>& table) {
    std::set<std::string_view> names;
    std::set<Enum> values;
    for (const NamedValue<Enum>& entry : table) {
        EXPECT_TRUE(names.insert(entry.name).second) << entry.name;
        EXPECT_TRUE(values.insert(entry.value).second) << entry.name;
        ASSERT_TRUE(value_in(table, entry.name).has_value()) << entry.name;
        EXPECT_EQ(*value_in(table, entry.name), entry.value);
        EXPECT_STREQ(name_in(table, entry.value), entry.name);
    }
    EXPECT_FALSE(value_in(table, "").has_value());
    EXPECT_FALSE(value_in(table, "no-such-name").has_value());
}

TEST(NameTables, EveryTableReadsBothWays) {
    expect_round_trip(kRenderModeNames);
    expect_round_trip(kCriterionNames);
    expect_round_trip(kBoundSearchNames);
    expect_round_trip(kRepresentativesNames);
    expect_round_trip(kPrimaryChoiceNames);
    expect_round_trip(kPrimaryVisibilityNames);
    expect_round_trip(kShadowModeNames);
    expect_round_trip(kSppMethodNames);
}

TEST(NameTables, ModesAreListedInKeyOrder) {
    // The view's number keys and the editor's list both follow the table.
    ASSERT_EQ(kRenderModeCount, 6);
    EXPECT_EQ(index_in(kRenderModeNames, RenderMode::kReference), 0u);
    EXPECT_EQ(index_in(kRenderModeNames, RenderMode::kRealtime), 4u);
    EXPECT_EQ(index_in(kRenderModeNames, RenderMode::kRestir), 5u);
    EXPECT_STREQ(names_of(kRenderModeNames)[3], "cutsize");
    EXPECT_EQ(names_in(kCriterionNames), "radius, bound");
    EXPECT_STREQ(name_in(kCriterionNames, static_cast<CutCriterion>(9)), "unknown");
}

TEST(NameTables, OldParsersReadTheTables) {
    EXPECT_EQ(parse_render_mode("cutsize"), RenderMode::kCutSize);
    EXPECT_EQ(parse_spp_method("reconstruction"), SppMethod::kReconstruction);
    ASSERT_TRUE(parse_shadow_mode("off"));
    EXPECT_EQ(*parse_shadow_mode("off"), ShadowMode::kOff);
    Result<ShadowMode> bad = parse_shadow_mode("maybe");
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().find("auto, on, off"), std::string::npos) << bad.error();
}

// Parses `args` (after the program's name) into a command with the shared flags.
SharedRenderFlags parse_shared(std::vector<std::string> args) {
    CLI::App app;
    SharedRenderFlags flags;
    add_shared_render_flags(app, flags);
    std::reverse(args.begin(), args.end());  // CLI11 takes them last first
    app.parse(args);
    return flags;
}

TEST(EnumFlags, NamesParseStraightIntoTheEnums) {
    const SharedRenderFlags flags =
        parse_shared({"--shadows", "off", "--primary", "rays", "--representatives", "importance",
                      "--realtime-cut", "8", "--realtime-rays", "3"});
    EXPECT_EQ(flags.shadows, ShadowMode::kOff);
    EXPECT_EQ(flags.primary, PrimaryChoice::kRays);
    EXPECT_EQ(flags.representatives, Representatives::kImportance);
    EXPECT_EQ(flags.realtime_cut, 8u);
    EXPECT_EQ(flags.realtime_rays, 3u);
    const SharedRenderFlags defaults = parse_shared({});
    EXPECT_EQ(defaults.shadows, ShadowMode::kAuto);
    EXPECT_EQ(defaults.primary, PrimaryChoice::kAuto);
    EXPECT_EQ(defaults.representatives, Representatives::kTree);
}

TEST(EnumFlags, AWrongNameListsTheNames) {
    try {
        parse_shared({"--shadows", "maybe"});
        FAIL() << "--shadows maybe was accepted";
    } catch (const CLI::ValidationError& e) {
        EXPECT_NE(std::string(e.what()).find("'maybe' is not one of auto, on, off"), std::string::npos)
            << e.what();
    }
    // The value a name stands for is not a name.
    EXPECT_THROW(parse_shared({"--primary", "1"}), CLI::ValidationError);
}

TEST(EnumFlags, RealtimeRaysAreRangeChecked) {
    // One registration for render and view: both refuse a budget over the most.
    EXPECT_THROW(parse_shared({"--realtime-rays", std::to_string(kMaxStochasticRays + 1)}),
                 CLI::ValidationError);
    EXPECT_EQ(parse_shared({"--realtime-rays", std::to_string(kMaxStochasticRays)}).realtime_rays,
              kMaxStochasticRays);
}

}  // namespace
}  // namespace lc::client
