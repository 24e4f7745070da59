// HOST:PORT and token files, read by one parser each for both programs
// (protocol/endpoint.h, protocol/token_file.h).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "protocol/endpoint.h"
#include "protocol/token_file.h"
#include "test_paths.h"

namespace lc {
namespace {

TEST(Endpoint, ReadsHostAndPort) {
    Result<Endpoint> plain = parse_endpoint("127.0.0.1:7000");
    ASSERT_TRUE(plain.ok()) << plain.error();
    EXPECT_EQ(plain->host, "127.0.0.1");
    EXPECT_EQ(plain->port, 7000);
    Result<Endpoint> v6 = parse_endpoint("[::1]:65535");
    ASSERT_TRUE(v6.ok()) << v6.error();
    EXPECT_EQ(v6->host, "::1");
    EXPECT_EQ(v6->port, 65535);
    Result<Endpoint> any_port = parse_endpoint("localhost:0");
    ASSERT_TRUE(any_port.ok()) << any_port.error();
    EXPECT_EQ(any_port->port, 0);
}

TEST(Endpoint, RefusesWhatIsNotHostColonPort) {
    for (const char* text : {"localhost", ":7000", "h:", "h:65536", "h:-1", "h:+80", "h:7a", "h: 80", "h:999999"}) {
        Result<Endpoint> refused = parse_endpoint(text);
        ASSERT_FALSE(refused.ok()) << text;
        EXPECT_NE(refused.error().find(text), std::string::npos) << refused.error();
    }
}

std::filesystem::path token_file(const std::string& name, const std::string& bytes) {
    const std::filesystem::path path = test::make_temp_dir("token_file") / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

TEST(TokenFile, DropsTheWhiteSpaceAroundTheFirstLine) {
    const std::string token = "correct-horse-battery-staple";
    for (const std::string& bytes : {token, token + "\n", "  " + token + " \r\n", "\t" + token + "\nsecond line\n"}) {
        Result<std::string> read = read_token_file(token_file("t", bytes));
        ASSERT_TRUE(read.ok()) << read.error();
        EXPECT_EQ(read.value(), token);
    }
}

TEST(TokenFile, RefusesMissingEmptyShortAndHugeFiles) {
    EXPECT_NE(read_token_file("/nonexistent/token").error().find("cannot read"), std::string::npos);
    EXPECT_NE(read_token_file(token_file("empty", " \n")).error().find("empty"), std::string::npos);
    EXPECT_NE(read_token_file(token_file("short", "  fifteen-chars!")).error().find("too short"), std::string::npos);
    EXPECT_TRUE(read_token_file(token_file("sixteen", "sixteen-chars!!!")).ok());
    const std::string huge(kMaxTokenFileBytes + 1, 'x');
    EXPECT_NE(read_token_file(token_file("huge", huge)).error().find("over"), std::string::npos);
}

}  // namespace
}  // namespace lc
