#pragma once
// The environment flags shared by bake, render and view: an equirectangular
// HDR map (--environment FILE, --environment-intensity, --environment-rotation)
// or a Preetham sun and sky (--sky ELEVATION,AZIMUTH,TURBIDITY), and how many
// directional lights the server makes of it (--environment-lights).
#include <CLI/CLI.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "lightcuts/environment.h"
#include "lightcuts/result.h"

namespace lc::client {

struct EnvironmentFlags {
    std::string file;
    std::string sky;
    float intensity = 1.0f;
    float rotation_deg = 0.0f;
    std::optional<uint32_t> lights;  // none: the server's default

    void add_to(CLI::App& cmd);
    bool requested() const { return !file.empty() || !sky.empty(); }
    // The flags' environment, or `named` (the scene's, Scene::environment)
    // when neither --environment nor --sky was given: the flags override the
    // file. An error names the problem.
    Result<std::shared_ptr<const Environment>> load(std::shared_ptr<const Environment> named = nullptr) const;
};

}  // namespace lc::client
