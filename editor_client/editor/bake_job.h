#pragma once
// One bake running on its own thread, so the editor's window keeps drawing
// while the server builds and streams the tree. The UI thread polls progress
// and, once finished(), takes the outcome and imports it itself: the tree the
// renderer reads is only ever swapped on the UI thread.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "editor_client/bake/bake_client.h"
#include "lightcuts/guid.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"

namespace lc::client {

struct BakeProgress {
    std::string stage;     // the server's last stage name ("" before the first message)
    float percent = 0.0f;  // 0..100 within that stage
};

class BakeJob {
public:
    // Copies the lights and starts bake_lights on a new thread. `options`'
    // on_progress, on_warning and cancel are replaced by the job's own.
    BakeJob(std::span<const SceneLight> lights, const Guid& scene_guid, BakeClientOptions options);
    // Cancels a bake still running and waits for its thread.
    ~BakeJob();
    BakeJob(const BakeJob&) = delete;
    BakeJob& operator=(const BakeJob&) = delete;

    // The GUID of the scene content that was sent (to tell whether the tree
    // still matches the scene once edits happened during the bake).
    const Guid& scene_guid() const { return scene_guid_; }
    size_t light_count() const { return light_count_; }

    BakeProgress progress() const;
    // Warnings received so far, in order.
    std::vector<std::string> warnings() const;
    // Thread-safe: the bake's I/O is woken to send Cancel at once.
    void cancel();
    bool cancel_requested() const { return cancel_.load(); }
    bool finished() const { return finished_.load(std::memory_order_acquire); }
    // Blocks until the thread is done (tests and scripts without a window).
    void wait();

    // Once finished(): the bake's outcome, moved out (a second call gives an
    // error). Before: an error saying the bake is still running.
    Result<BakeOutcome> take_outcome();

private:
    void run(std::vector<SceneLight> lights, BakeClientOptions options);

    Guid scene_guid_;
    size_t light_count_ = 0;
    std::atomic<bool> cancel_{false};
    BakeWaker waker_;
    std::atomic<bool> finished_{false};
    mutable std::mutex mutex_;  // guards progress_, warnings_, outcome_, taken_
    BakeProgress progress_;
    std::vector<std::string> warnings_;
    std::optional<Result<BakeOutcome>> outcome_;
    bool taken_ = false;
    std::thread thread_;  // last: started after every other member exists
};

}  // namespace lc::client
