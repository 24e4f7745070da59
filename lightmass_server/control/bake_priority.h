#pragma once
// Bake threads run below the I/O thread's CPU priority (a higher nice value),
// so on a machine whose cores a bake fills, accepting a connection and
// answering a status request never wait behind bake work. Linux keeps a nice
// value per thread and a thread inherits its creator's, so the lane threads
// lower themselves and the observer lowers TBB's workers as they join.
#include <tbb/task_scheduler_observer.h>

namespace lc::bake {

// Raises the calling thread's nice value to `nice` (0..19); never lowers it, so
// a server started under `nice` keeps its level. False where the system refused.
bool lower_this_thread_priority(int nice);
// The calling thread's nice value.
int this_thread_nice();

// While alive, every TBB worker thread that enters the arena runs at `nice`.
class BakeWorkerPriority : public tbb::task_scheduler_observer {
public:
    explicit BakeWorkerPriority(int nice);
    ~BakeWorkerPriority() override;
    void on_scheduler_entry(bool is_worker) override;

private:
    int nice_;
};

}  // namespace lc::bake
