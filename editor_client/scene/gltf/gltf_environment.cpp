#include "editor_client/scene/gltf/gltf_environment.h"

#include <cmath>
#include <string>
#include <vector>

#include "editor_client/scene/inputs/environment_image.h"
#include "lightcuts/status_macros.h"
#include "protocol/environment_records.h"

namespace lc::client {
namespace {

std::string field_name(const char* key, const char* field) {
    return std::string("asset.extras.") + key + "." + field;
}

// A number field into `out`, which keeps its value when the field is absent
// and not required.
Status read_number(const tinygltf::Value& object, const char* key, const char* field, float& out,
                   bool required) {
    if (!object.Has(field)) {
        if (required) return make_error(field_name(key, field) + " is missing");
        return Ok{};
    }
    const tinygltf::Value& v = object.Get(field);
    if (!v.IsNumber()) return make_error(field_name(key, field) + " is not a number");
    const double value = v.GetNumberAsDouble();
    if (!std::isfinite(value) || std::abs(value) > 3.0e38)
        return make_error(field_name(key, field) + " is " + std::to_string(value) + ": not a finite float");
    out = float(value);
    return Ok{};
}

Status check_intensity(float intensity, const char* key) {
    if (intensity < 0.0f)
        return make_error(field_name(key, "intensity") + " is " + std::to_string(intensity) +
                          ": it must be >= 0");
    return Ok{};
}

Result<GltfEnvironment> read_map(const tinygltf::Value& object, GltfResourceAccess& access) {
    const char* key = kEnvironmentExtrasKey;
    if (!object.Has("image") || !object.Get("image").IsString())
        return make_error(field_name(key, "image") + " is missing or not a string (the .hdr file's URI)");
    const std::string uri = object.Get("image").Get<std::string>();
    if (uri.empty()) return make_error(field_name(key, "image") + " is empty");
    auto environment = std::make_shared<Environment>();
    LC_RETURN_IF_ERROR(read_number(object, key, "intensity", environment->intensity, false));
    LC_RETURN_IF_ERROR(check_intensity(environment->intensity, key));
    LC_RETURN_IF_ERROR(read_number(object, key, "rotation", environment->rotation_deg, false));
    std::vector<unsigned char> bytes;
    std::string error;
    GltfEnvironment out;
    out.image = access.resolve(uri);
    if (!access.read_resource(out.image, bytes, error))
        return make_error(field_name(key, "image") + " '" + uri + "': " + error);
    Result<EquirectMap> map = decode_environment_image(bytes, field_name(key, "image") + " '" + uri + "'");
    if (!map) return map.failure();
    environment->map = std::move(map).value();
    LC_RETURN_IF_ERROR(validate_environment(*environment));
    out.environment = std::move(environment);
    return out;
}

Result<GltfEnvironment> read_sky(const tinygltf::Value& object) {
    const char* key = kSkyExtrasKey;
    auto environment = std::make_shared<Environment>();
    SkyParameters sky;
    LC_RETURN_IF_ERROR(read_number(object, key, "elevation", sky.elevation_deg, true));
    LC_RETURN_IF_ERROR(read_number(object, key, "azimuth", sky.azimuth_deg, true));
    LC_RETURN_IF_ERROR(read_number(object, key, "turbidity", sky.turbidity, true));
    if (Status valid = validate_sky_parameters(sky); !valid)
        return make_error(std::string("asset.extras.") + key + ": " + valid.error());
    LC_RETURN_IF_ERROR(read_number(object, key, "intensity", environment->intensity, false));
    LC_RETURN_IF_ERROR(check_intensity(environment->intensity, key));
    environment->sky = sky;
    LC_RETURN_IF_ERROR(validate_environment(*environment));
    GltfEnvironment out;
    out.environment = std::move(environment);
    return out;
}

}  // namespace

Result<GltfEnvironment> read_gltf_environment(const tinygltf::Value& asset_extras,
                                              GltfResourceAccess& access) {
    if (!asset_extras.IsObject()) return GltfEnvironment{};
    const bool map = asset_extras.Has(kEnvironmentExtrasKey);
    const bool sky = asset_extras.Has(kSkyExtrasKey);
    if (map && sky)
        return make_error(std::string("asset.extras names both ") + kEnvironmentExtrasKey + " and " +
                          kSkyExtrasKey + "; an environment is one or the other");
    const char* key = map ? kEnvironmentExtrasKey : kSkyExtrasKey;
    if (!map && !sky) return GltfEnvironment{};
    const tinygltf::Value& object = asset_extras.Get(key);
    if (!object.IsObject()) return make_error(std::string("asset.extras.") + key + " is not an object");
    return map ? read_map(object, access) : read_sky(object);
}

void put_gltf_environment(const Scene& scene, const std::filesystem::path& out_folder,
                          nlohmann::json& asset) {
    if (asset.contains("extras") && asset["extras"].is_object()) {
        asset["extras"].erase(kEnvironmentExtrasKey);
        asset["extras"].erase(kSkyExtrasKey);
        if (asset["extras"].empty()) asset.erase("extras");
    }
    const Environment* environment = scene.environment.get();
    if (environment == nullptr || (!environment->has_sky() && scene.environment_image.empty())) return;
    if (!asset.contains("extras") || !asset["extras"].is_object()) asset["extras"] = nlohmann::json::object();
    nlohmann::json& extras = asset["extras"];
    if (environment->has_sky()) {
        const SkyParameters& sky = *environment->sky;
        extras[kSkyExtrasKey] = {{"elevation", sky.elevation_deg},
                                 {"azimuth", sky.azimuth_deg},
                                 {"turbidity", sky.turbidity},
                                 {"intensity", environment->intensity}};
        return;
    }
    extras[kEnvironmentExtrasKey] = {{"image", path_from(out_folder, scene.environment_image)},
                                     {"intensity", environment->intensity},
                                     {"rotation", environment->rotation_deg}};
}

std::string path_from(const std::filesystem::path& folder, const std::filesystem::path& file) {
    std::error_code ec;
    const std::filesystem::path target = std::filesystem::absolute(file, ec).lexically_normal();
    const std::filesystem::path from = std::filesystem::absolute(folder, ec).lexically_normal();
    const std::filesystem::path relative = target.lexically_relative(from);
    const bool inside = !relative.empty() && *relative.begin() != "..";
    return (inside ? relative : target).generic_string();
}

}  // namespace lc::client
