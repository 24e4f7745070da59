#pragma once
// A window without a display: frames are rendered but never presented, and
// the input is a script (tests drive the view loop with it).
#include <deque>

#include "editor_client/window/window.h"

namespace lc::client {

class HeadlessWindow final : public Window {
public:
    HeadlessWindow(uint32_t width, uint32_t height) : extent_{width, height} {}

    // Input delivered by the next poll(), one entry per poll, in order.
    void queue_input(const WindowInput& input) { script_.push_back(input); }
    const std::string& title() const { return title_; }

    std::vector<std::string> required_instance_extensions() const override { return {}; }
    bool has_surface() const override { return false; }
    Result<VkSurfaceKHR> create_surface(VkInstance) override {
        return make_error("a headless window has no surface");
    }
    VkExtent2D framebuffer_size() const override { return extent_; }
    WindowInput poll() override {
        if (script_.empty()) return {};
        WindowInput next = script_.front();
        script_.pop_front();
        return next;
    }
    void set_title(const std::string& title) override { title_ = title; }

private:
    VkExtent2D extent_;
    std::deque<WindowInput> script_;
    std::string title_;
};

}  // namespace lc::client
