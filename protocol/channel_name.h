#pragma once
// Channel names after Unreal's CreateChannelName(Guid, Version, Extension):
// "<VERSION as 32 upper-case hex>.<DATA GUID as 32 hex>.<extension>".
#include <optional>
#include <string>
#include <string_view>

#include "lightcuts/guid.h"

namespace lc {

// The thesis's Lightcuts result channel: data GUID "LightcutsDataGUI",
// version GUID 4C696768-74637574-73566572-7369666E, extension "lcut".
inline constexpr Guid kLightcutsDataGuid{0x4C696768u, 0x74637574u, 0x73446174u, 0x61475549u};
inline constexpr Guid kLightcutsVersionGuid{0x4C696768u, 0x74637574u, 0x73566572u, 0x7369666Eu};
inline constexpr const char* kLightcutsExtension = "lcut";

// Our scene-format version; the scene channel is named by the scene's GUID.
inline constexpr Guid kSceneFormatVersionGuid{0x4C435363u, 0x656E6546u, 0x6F726D61u, 0x74000001u};
inline constexpr const char* kSceneExtension = "scene";
// The scene's surfaces (protocol/geometry_channel.h), named like its scene channel.
inline constexpr const char* kGeometryExtension = "geom";

struct ChannelName {
    Guid version;
    Guid data;
    std::string extension;

    std::string to_string() const;
    static std::optional<ChannelName> parse(std::string_view text);
};

std::string create_channel_name(const Guid& data, const Guid& version, std::string_view extension);
std::string lightcuts_result_channel_name();
std::string scene_channel_name(const Guid& scene_guid);
std::string geometry_channel_name(const Guid& scene_guid);

}  // namespace lc
