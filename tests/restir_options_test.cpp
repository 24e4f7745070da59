// The ReSTIR mode's flags (commands/restir_options.h): defaults, parsed
// values, and errors that name the flag.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "editor_client/commands/restir_options.h"

namespace lc::client {
namespace {

// The error CLI11 or restir_settings_from gives for `args` ("" when none).
std::string parse_error(std::vector<std::string> args, RestirSettings* parsed = nullptr) {
    CLI::App app;
    RestirFlags flags;
    add_restir_options(&app, &flags);
    std::reverse(args.begin(), args.end());  // CLI11 takes them last first
    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        return e.what();
    }
    Result<RestirSettings> settings = restir_settings_from(flags);
    if (!settings) return settings.error();
    if (parsed != nullptr) *parsed = *settings;
    return "";
}

TEST(RestirOptions, DefaultsAreTheSettingsDefaults) {
    RestirSettings parsed;
    parsed.candidates = 99;
    EXPECT_EQ(parse_error({}, &parsed), "");
    EXPECT_EQ(parsed, RestirSettings{});
}

TEST(RestirOptions, ParsesEveryFlag) {
    RestirSettings parsed;
    EXPECT_EQ(parse_error({"--restir-candidates", "32", "--restir-source", "power", "--restir-spatial", "5",
                           "--restir-temporal", "off", "--restir-bias", "unbiased", "--restir-visibility", "on"},
                          &parsed),
              "");
    EXPECT_EQ(parsed.candidates, 32u);
    EXPECT_EQ(parsed.source, RestirSource::kPower);
    EXPECT_EQ(parsed.spatial, 5u);
    EXPECT_FALSE(parsed.temporal);
    EXPECT_EQ(parsed.bias, RestirBias::kUnbiased);
    EXPECT_TRUE(parsed.candidate_visibility);
}

TEST(RestirOptions, ErrorsNameTheFlag) {
    const std::vector<std::vector<std::string>> bad{
        {"--restir-candidates", "0"},  {"--restir-candidates", "65"}, {"--restir-source", "uniform"},
        {"--restir-spatial", "9"},     {"--restir-temporal", "yes"},  {"--restir-bias", "some"},
        {"--restir-visibility", "2"}};
    for (const std::vector<std::string>& args : bad) {
        const std::string error = parse_error(args);
        EXPECT_NE(error.find(args[0]), std::string::npos) << args[0] << " " << args[1] << ": " << error;
    }
}

TEST(RestirOptions, ValidateNamesTheOption) {
    RestirSettings settings;
    settings.candidates = 0;
    Status status = validate(settings);
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().find("--restir-candidates"), std::string::npos);
    settings.candidates = 8;
    settings.spatial = 9;
    status = validate(settings);
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().find("--restir-spatial"), std::string::npos);
}

}  // namespace
}  // namespace lc::client
