#pragma once
// --allow-external-resources, on every command that loads a glTF scene.
#include <CLI/CLI.hpp>

#include "editor_client/scene/gltf/gltf_loader.h"

namespace lc::client {

inline CLI::Option* add_gltf_load_flags(CLI::App& cmd, GltfLoadOptions& options) {
    return cmd.add_flag("--allow-external-resources", options.allow_external_resources,
                        "Let the scene's buffer and image URIs name files outside its folder "
                        "(absolute paths, ../); by default only data: URIs and files inside it");
}

}  // namespace lc::client
