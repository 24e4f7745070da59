#include "editor_client/editor/bake_job.h"

#include <utility>

namespace lc::client {

BakeJob::BakeJob(std::span<const SceneLight> lights, const Guid& scene_guid,
                 BakeClientOptions options)
    : scene_guid_(scene_guid), light_count_(lights.size()) {
    std::vector<SceneLight> copy(lights.begin(), lights.end());
    thread_ = std::thread(&BakeJob::run, this, std::move(copy), std::move(options));
}

BakeJob::~BakeJob() {
    cancel();
    if (thread_.joinable()) thread_.join();
}

void BakeJob::cancel() {
    cancel_.store(true);
    waker_.wake();
}

void BakeJob::run(std::vector<SceneLight> lights, BakeClientOptions options) {
    options.cancel = &cancel_;
    options.waker = &waker_;
    options.on_progress = [this](const ProgressMsg& message) {
        std::lock_guard lock(mutex_);
        progress_.stage = message.stage;
        progress_.percent = message.percent;
    };
    options.on_warning = [this](const std::string& text) {
        std::lock_guard lock(mutex_);
        warnings_.push_back(text);
    };
    Result<BakeOutcome> outcome = bake_lights(lights, scene_guid_, options);
    // A bake cancelled while, say, the connection failed still reports as cancelled.
    if (!outcome && cancel_.load() && outcome.error_kind() != ErrorKind::kCancelled)
        outcome = make_error("bake cancelled (" + outcome.error() + ")", ErrorKind::kCancelled);
    {
        std::lock_guard lock(mutex_);
        outcome_ = std::move(outcome);
    }
    finished_.store(true, std::memory_order_release);
}

BakeProgress BakeJob::progress() const {
    std::lock_guard lock(mutex_);
    return progress_;
}

std::vector<std::string> BakeJob::warnings() const {
    std::lock_guard lock(mutex_);
    return warnings_;
}

void BakeJob::wait() {
    if (thread_.joinable()) thread_.join();
}

Result<BakeOutcome> BakeJob::take_outcome() {
    if (!finished()) return make_error("the bake is still running");
    std::lock_guard lock(mutex_);
    if (taken_ || !outcome_) return make_error("the bake's outcome was already taken");
    taken_ = true;
    Result<BakeOutcome> outcome = std::move(*outcome_);
    outcome_.reset();
    return outcome;
}

}  // namespace lc::client
