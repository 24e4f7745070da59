#pragma once
// The server's log as journald reads it: when stderr is the journal (systemd
// sets $JOURNAL_STREAM), each line starts with its syslog priority ("<4>" for
// a warning), so `journalctl -p warning` filters by level, and carries no
// timestamp or colour of its own (the journal stamps each line).
#include <spdlog/logger.h>

namespace lc::bake {

// True when systemd connected stderr to the journal.
bool stderr_is_journal();

// Sets `logger`'s lines to "<PRIORITY>message".
void use_journal_format(spdlog::logger& logger);

}  // namespace lc::bake
