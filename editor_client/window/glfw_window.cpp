#include "editor_client/window/glfw_window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <mutex>

#include "editor_client/vk/vk_result.h"

namespace lc::client {
namespace {

// glfwInit/glfwTerminate are process-wide; windows count their users.
std::mutex g_glfw_mutex;
int g_glfw_users = 0;

std::string last_glfw_error() {
    const char* description = nullptr;
    int code = glfwGetError(&description);
    if (code == GLFW_NO_ERROR) return "unknown GLFW error";
    return description != nullptr ? description : "GLFW error " + std::to_string(code);
}

}  // namespace

Result<std::unique_ptr<GlfwWindow>> GlfwWindow::create(uint32_t width, uint32_t height,
                                                       const std::string& title) {
    {
        std::lock_guard lock(g_glfw_mutex);
        if (g_glfw_users == 0 && glfwInit() != GLFW_TRUE)
            return make_error("cannot open a window: " + last_glfw_error() +
                              " (no display? run under xvfb-run -a)");
        ++g_glfw_users;
    }
    std::unique_ptr<GlfwWindow> window(new GlfwWindow());
    if (glfwVulkanSupported() != GLFW_TRUE)
        return make_error("GLFW found no Vulkan loader for window surfaces");
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    window->window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (window->window_ == nullptr) return make_error("cannot create a window: " + last_glfw_error());
    glfwSetWindowUserPointer(window->window_, window.get());
    glfwSetKeyCallback(window->window_, &GlfwWindow::on_key);
    glfwSetCursorPosCallback(window->window_, &GlfwWindow::on_cursor);
    glfwSetScrollCallback(window->window_, &GlfwWindow::on_scroll);
    return window;
}

GlfwWindow::~GlfwWindow() {
    if (window_ != nullptr) glfwDestroyWindow(window_);
    std::lock_guard lock(g_glfw_mutex);
    if (--g_glfw_users == 0) glfwTerminate();
}

std::vector<std::string> GlfwWindow::required_instance_extensions() const {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    std::vector<std::string> out;
    for (uint32_t i = 0; i < count; ++i) out.emplace_back(names[i]);
    return out;
}

Result<VkSurfaceKHR> GlfwWindow::create_surface(VkInstance instance) {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    LC_VK_CHECK(glfwCreateWindowSurface(instance, window_, nullptr, &surface));
    return surface;
}

VkExtent2D GlfwWindow::framebuffer_size() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))};
}

WindowInput GlfwWindow::poll() {
    glfwPollEvents();
    WindowInput input = pending_;
    if (!ui_keyboard_) {
        auto held = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS ? 1.0f : 0.0f; };
        input.fly = {held(GLFW_KEY_D) - held(GLFW_KEY_A), held(GLFW_KEY_R) - held(GLFW_KEY_F),
                     held(GLFW_KEY_W) - held(GLFW_KEY_S)};
    }
    input.close_requested = glfwWindowShouldClose(window_) == GLFW_TRUE;
    pending_ = WindowInput{};
    return input;
}

void GlfwWindow::set_title(const std::string& title) {
    glfwSetWindowTitle(window_, title.c_str());
}

void GlfwWindow::on_key(GLFWwindow* window, int key, int, int action, int) {
    auto* self = static_cast<GlfwWindow*>(glfwGetWindowUserPointer(window));
    if (action != GLFW_PRESS || self->ui_keyboard_) return;
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_5) self->pending_.mode_key = key - GLFW_KEY_1 + 1;
    if (key == GLFW_KEY_ESCAPE || key == GLFW_KEY_Q) glfwSetWindowShouldClose(window, GLFW_TRUE);
}

void GlfwWindow::on_cursor(GLFWwindow* window, double x, double y) {
    auto* self = static_cast<GlfwWindow*>(glfwGetWindowUserPointer(window));
    if (self->have_cursor_ && !self->ui_mouse_) {
        glm::vec2 delta(float(x - self->last_x_), float(y - self->last_y_));
        const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                           glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
        if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS)
            (shift ? self->pending_.look_drag : self->pending_.orbit_drag) += delta;
        if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS)
            self->pending_.pan_drag += delta;
    }
    self->last_x_ = x;
    self->last_y_ = y;
    self->have_cursor_ = true;
}

void GlfwWindow::on_scroll(GLFWwindow* window, double, double dy) {
    auto* self = static_cast<GlfwWindow*>(glfwGetWindowUserPointer(window));
    if (!self->ui_mouse_) self->pending_.scroll += float(dy);
}

}  // namespace lc::client
