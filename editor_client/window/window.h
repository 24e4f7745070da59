#pragma once
// Where the view command's frames go and where its input comes from: a GLFW
// window on a display, or a headless stand-in (tests, machines without one).
#include <vulkan/vulkan.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <vector>

#include "lightcuts/result.h"

namespace lc::client {

// What happened since the last poll.
struct WindowInput {
    glm::vec2 orbit_drag{0.0f};   // pixels dragged with the left button held
    glm::vec2 pan_drag{0.0f};     // pixels dragged with the right button held
    glm::vec2 look_drag{0.0f};    // pixels dragged with Shift and the left button held
    // Fly keys held now, each axis -1, 0 or 1: x right (D/A), y up (R/F), z forward (W/S).
    glm::vec3 fly{0.0f};
    float scroll = 0.0f;          // wheel steps, positive away from the user
    std::optional<int> mode_key;  // 1..4 pressed (the last one wins)
    bool close_requested = false;
};

class Window {
public:
    virtual ~Window() = default;

    // Instance extensions the surface needs (empty without a surface).
    virtual std::vector<std::string> required_instance_extensions() const = 0;
    // False for a headless window: frames are rendered but not presented.
    virtual bool has_surface() const = 0;
    // The caller owns the surface (vk::Surface) and destroys it before the instance.
    virtual Result<VkSurfaceKHR> create_surface(VkInstance instance) = 0;
    virtual VkExtent2D framebuffer_size() const = 0;
    virtual WindowInput poll() = 0;
    virtual void set_title(const std::string& title) = 0;
};

}  // namespace lc::client
