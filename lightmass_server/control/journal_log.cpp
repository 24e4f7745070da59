#include "lightmass_server/control/journal_log.h"

#include <spdlog/pattern_formatter.h>

#include <cstdlib>
#include <memory>
#include <string_view>

namespace lc::bake {
namespace {

// spdlog's level as a syslog priority prefix: debug 7, info 6, warning 4, error 3, critical 2.
class SyslogPriority : public spdlog::custom_flag_formatter {
public:
    void format(const spdlog::details::log_msg& message, const std::tm&, spdlog::memory_buf_t& out) override {
        std::string_view prefix = "<6>";
        switch (message.level) {
            case spdlog::level::trace:
            case spdlog::level::debug: prefix = "<7>"; break;
            case spdlog::level::warn: prefix = "<4>"; break;
            case spdlog::level::err: prefix = "<3>"; break;
            case spdlog::level::critical: prefix = "<2>"; break;
            default: break;
        }
        out.append(prefix.data(), prefix.data() + prefix.size());
    }
    std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<SyslogPriority>(); }
};

}  // namespace

bool stderr_is_journal() {
    const char* stream = std::getenv("JOURNAL_STREAM");
    return stream && *stream;
}

void use_journal_format(spdlog::logger& logger) {
    auto formatter = std::make_unique<spdlog::pattern_formatter>();
    formatter->add_flag<SyslogPriority>('*').set_pattern("%*%v");
    logger.set_formatter(std::move(formatter));
}

}  // namespace lc::bake
