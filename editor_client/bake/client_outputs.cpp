#include "editor_client/bake/client_outputs.h"

#include <chrono>
#include <type_traits>
#include <utility>

#include "lightcuts/status_macros.h"

namespace lc::client {

Status ClientOutputs::apply(const ClientActions& actions) {
    for (const ClientAction& action : actions) LC_RETURN_IF_ERROR(apply_one(action));
    return Ok{};
}

Status ClientOutputs::apply_one(const ClientAction& action) {
    namespace act = client_action;
    return std::visit(
        [&](const auto& a) -> Status {
            using A = std::decay_t<decltype(a)>;
            if constexpr (std::is_same_v<A, act::ReportProgress>) {
                if (options_.on_progress) options_.on_progress(a.progress);
            } else if constexpr (std::is_same_v<A, act::ReportWarning>) {
                if (options_.on_warning) options_.on_warning(a.text);
            } else if constexpr (std::is_same_v<A, act::RecordChannel>) {
                if (options_.recorder && options_.recorder->enabled())
                    return options_.recorder->record(a.name, a.bytes);
            } else if constexpr (std::is_same_v<A, act::OpenDump>) {
                return open_dump(a);
            } else if constexpr (std::is_same_v<A, act::AppendDump>) {
                if (!dump_) return make_error("the result's dump was written before it was opened");
                return dump_->append(a.bytes);
            } else if constexpr (std::is_same_v<A, act::CommitDump>) {
                return commit_dump();
            } else if constexpr (std::is_same_v<A, act::DiscardDump>) {
                dump_.reset();  // uncommitted: its temporary file goes
            }
            return Ok{};
        },
        action);
}

Status ClientOutputs::open_dump(const client_action::OpenDump& open) {
    if (options_.result_dump.empty())
        return make_error("the bake writes a dump but was given no path for it");
    Result<DumpWriter> dump = DumpWriter::open(options_.result_dump, open.channel_name, open.total_bytes);
    if (!dump) return dump.failure();
    dump_.emplace(std::move(dump.value()));
    return Ok{};
}

Status ClientOutputs::commit_dump() {
    if (!dump_) return make_error("the result's dump was committed before it was opened");
    const auto start = std::chrono::steady_clock::now();
    Status committed = dump_->commit();
    dump_.reset();
    commit_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return committed;
}

}  // namespace lc::client
