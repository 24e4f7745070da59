#pragma once
// A GLFW window with a Vulkan surface (no OpenGL context), collecting mouse
// and key input for the view command.
#include <memory>
#include <string>

#include "editor_client/window/window.h"

struct GLFWwindow;

namespace lc::client {

class GlfwWindow final : public Window {
public:
    // Fails with a message when no display is reachable (run under xvfb-run -a).
    static Result<std::unique_ptr<GlfwWindow>> create(uint32_t width, uint32_t height,
                                                      const std::string& title);
    ~GlfwWindow() override;
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;

    std::vector<std::string> required_instance_extensions() const override;
    bool has_surface() const override { return true; }
    Result<VkSurfaceKHR> create_surface(VkInstance instance) override;
    VkExtent2D framebuffer_size() const override;
    WindowInput poll() override;
    void set_title(const std::string& title) override;

    // For the ImGui backend, which installs its callbacks after ours.
    GLFWwindow* handle() const { return window_; }
    // While the panels hold the mouse or keyboard, drags, the wheel and keys
    // are theirs: they neither move the camera nor switch modes or close.
    void set_ui_capture(bool mouse, bool keyboard) {
        ui_mouse_ = mouse;
        ui_keyboard_ = keyboard;
    }

private:
    GlfwWindow() = default;

    static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);
    static void on_cursor(GLFWwindow* window, double x, double y);
    static void on_scroll(GLFWwindow* window, double dx, double dy);

    GLFWwindow* window_ = nullptr;
    WindowInput pending_;
    double last_x_ = 0.0, last_y_ = 0.0;
    bool have_cursor_ = false;
    bool ui_mouse_ = false;
    bool ui_keyboard_ = false;
};

}  // namespace lc::client
