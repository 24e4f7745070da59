#pragma once
// How a subcommand fails (commands.h): print "error: MESSAGE" and throw
// CLI::RuntimeError(1), which main turns into the exit status. The or_fail
// forms unwrap a Result / Status, failing with its message.
#include <string>
#include <utility>

#include "lightcuts/result.h"

namespace lc::client {

[[noreturn]] void fail(const std::string& message);

template <typename T>
T or_fail(Result<T> result) {
    if (!result) fail(result.error());
    return std::move(result).value();
}

inline void or_fail(const Status& status) {
    if (!status) fail(status.error());
}

}  // namespace lc::client
