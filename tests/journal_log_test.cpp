// The server's log under systemd: each line carries its level as a syslog
// priority journald reads ("<4>" a warning), and nothing else of spdlog's.
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <sstream>

#include "lightmass_server/control/journal_log.h"

namespace lc::bake {
namespace {

TEST(JournalLog, EachLineStartsWithItsSyslogPriority) {
    std::ostringstream text;
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(text);
    spdlog::logger logger("journal-test", sink);
    logger.set_level(spdlog::level::debug);
    use_journal_format(logger);
    logger.debug("d");
    logger.info("listening");
    logger.warn("bake {} stopped", 3);
    logger.error("cannot write");
    logger.critical("out of memory");
    EXPECT_EQ(text.str(), "<7>d\n<6>listening\n<4>bake 3 stopped\n<3>cannot write\n<2>out of memory\n");
}

TEST(JournalLog, TheJournalIsToldByJournalStream) {
    ASSERT_EQ(setenv("JOURNAL_STREAM", "8:12345", 1), 0);
    EXPECT_TRUE(stderr_is_journal());
    ASSERT_EQ(unsetenv("JOURNAL_STREAM"), 0);
    EXPECT_FALSE(stderr_is_journal());
}

}  // namespace
}  // namespace lc::bake
