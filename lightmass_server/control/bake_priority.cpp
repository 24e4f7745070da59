#include "lightmass_server/control/bake_priority.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>

namespace lc::bake {
namespace {

// PRIO_PROCESS with a thread id addresses that one thread on Linux.
id_t this_thread_id() {
    return id_t(syscall(SYS_gettid));
}

}  // namespace

int this_thread_nice() {
    errno = 0;
    return getpriority(PRIO_PROCESS, this_thread_id());
}

bool lower_this_thread_priority(int nice) {
    if (nice <= 0 || this_thread_nice() >= nice) return true;
    return setpriority(PRIO_PROCESS, this_thread_id(), nice) == 0;
}

BakeWorkerPriority::BakeWorkerPriority(int nice) : tbb::task_scheduler_observer(), nice_(nice) {
    if (nice_ > 0) observe(true);
}

BakeWorkerPriority::~BakeWorkerPriority() {
    observe(false);
}

void BakeWorkerPriority::on_scheduler_entry(bool is_worker) {
    // The lane thread that starts a parallel loop lowered itself already.
    if (is_worker) lower_this_thread_priority(nice_);
}

}  // namespace lc::bake
