#pragma once
// The environment a glTF file names, read by the loader and written by the
// writer. It lives in the asset's extras, one of:
//   "asset": {"extras": {"lightcuts_environment":
//       {"image": "sky.hdr", "intensity": 1.0, "rotation": 0.0}}}
//   "asset": {"extras": {"lightcuts_sky":
//       {"elevation": 45.0, "azimuth": 0.0, "turbidity": 3.0, "intensity": 1.0}}}
// as --environment/--environment-intensity/--environment-rotation (degrees)
// and --sky ELEVATION,AZIMUTH,TURBIDITY give them; intensity defaults to 1 and
// rotation to 0. "image" is a URI resolved like the file's buffers and images:
// relative to the scene's folder and confined to it unless
// --allow-external-resources (gltf_resource_access.h). The command line's
// environment flags replace what the file names. Errors name the field.
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <filesystem>
#include <memory>
#include <string>

#include "editor_client/scene/gltf/gltf_resource_access.h"
#include "lightcuts/environment.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

inline constexpr const char* kEnvironmentExtrasKey = "lightcuts_environment";
inline constexpr const char* kSkyExtrasKey = "lightcuts_sky";

struct GltfEnvironment {
    std::shared_ptr<const Environment> environment;  // null: the file names none
    std::filesystem::path image;                     // the map's file as read
};

// From the asset's extras as tinygltf parsed them; the map is read through `access`.
Result<GltfEnvironment> read_gltf_environment(const tinygltf::Value& asset_extras,
                                              GltfResourceAccess& access);

// Puts the scene's environment (if any) into the glTF `asset` object's
// extras, replacing one named before; a map's image is named relative to
// `out_folder` when it lies inside it, else by its absolute path.
void put_gltf_environment(const Scene& scene, const std::filesystem::path& out_folder,
                          nlohmann::json& asset);
// `file` as the environment's "image" of a glTF in `folder`: relative when
// inside it, else absolute.
std::string path_from(const std::filesystem::path& folder, const std::filesystem::path& file);

}  // namespace lc::client
