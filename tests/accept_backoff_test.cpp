// The accept loop's back-off after failed accepts (out of file descriptors):
// growing waits up to a cap, and one log line per interval, not one per failure.
#include <gtest/gtest.h>

#include "lightmass_server/net/accept_backoff.h"

namespace lc::bake {
namespace {

using namespace std::chrono_literals;

TEST(AcceptBackoff, WaitsLongerAfterEachFailureUpToTheCap) {
    AcceptBackoff backoff;
    const auto now = AcceptBackoff::Clock::now();
    std::chrono::milliseconds expected = kFirstAcceptRetry;
    for (int i = 0; i < 20; ++i) {
        EXPECT_EQ(backoff.on_failure("Too many open files", now).delay, expected) << i;
        expected = std::min(expected * 2, kMaxAcceptRetry);
    }
    EXPECT_EQ(backoff.on_failure("Too many open files", now).delay, kMaxAcceptRetry);
}

TEST(AcceptBackoff, LogsOneLinePerIntervalCountingTheFailures) {
    AcceptBackoff backoff;
    const auto start = AcceptBackoff::Clock::now();
    AcceptRetry first = backoff.on_failure("Too many open files", start);
    ASSERT_TRUE(first.log_line);
    EXPECT_NE(first.log_line->find("Too many open files"), std::string::npos);
    int lines = 0;
    for (int i = 1; i <= 1000; ++i)
        lines += backoff.on_failure("Too many open files", start + i * 1ms).log_line ? 1 : 0;
    EXPECT_EQ(lines, 0);  // 1,000 failures within a second: no more lines
    AcceptRetry later = backoff.on_failure("Too many open files", start + kAcceptLogInterval + 1s);
    ASSERT_TRUE(later.log_line);
    EXPECT_NE(later.log_line->find("1001 failures"), std::string::npos) << *later.log_line;
}

TEST(AcceptBackoff, SuccessResetsTheWaitAndSaysSo) {
    AcceptBackoff backoff;
    EXPECT_FALSE(backoff.on_success());  // nothing to report without failures
    const auto now = AcceptBackoff::Clock::now();
    for (int i = 0; i < 5; ++i) backoff.on_failure("Too many open files", now);
    std::optional<std::string> recovered = backoff.on_success();
    ASSERT_TRUE(recovered);
    EXPECT_NE(recovered->find("5 failed accepts"), std::string::npos) << *recovered;
    AcceptRetry again = backoff.on_failure("Too many open files", now);
    EXPECT_EQ(again.delay, kFirstAcceptRetry);
    EXPECT_TRUE(again.log_line);
}

}  // namespace
}  // namespace lc::bake
