// Channel names: "<VERSION hex>.<DATA hex>.<extension>" (Unreal's CreateChannelName).
#include "channel_name.h"

namespace lc {
namespace {

constexpr size_t kGuidDigits = 32;
constexpr size_t kMaxExtensionLength = 64;

// Extensions end up in dump file names, so only a safe alphabet is accepted.
bool is_valid_extension(std::string_view extension) {
    if (extension.empty() || extension.size() > kMaxExtensionLength) return false;
    for (char c : extension) {
        const bool alnum =
            (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
        if (!alnum && c != '_' && c != '-') return false;
    }
    return true;
}

// Exactly 32 hex digits: the channel form never has separators.
std::optional<Guid> parse_digits(std::string_view text) {
    if (text.size() != kGuidDigits) return std::nullopt;
    return Guid::parse(text);
}

}  // namespace

std::string ChannelName::to_string() const {
    std::string text = version.to_hex();
    text += '.';
    text += data.to_hex();
    text += '.';
    text += extension;
    return text;
}

std::optional<ChannelName> ChannelName::parse(std::string_view text) {
    if (text.size() < 2 * kGuidDigits + 3) return std::nullopt;
    if (text[kGuidDigits] != '.' || text[2 * kGuidDigits + 1] != '.') return std::nullopt;
    auto version = parse_digits(text.substr(0, kGuidDigits));
    auto data = parse_digits(text.substr(kGuidDigits + 1, kGuidDigits));
    std::string_view extension = text.substr(2 * kGuidDigits + 2);
    if (!version || !data || !is_valid_extension(extension)) return std::nullopt;
    return ChannelName{*version, *data, std::string(extension)};
}

std::string create_channel_name(const Guid& data, const Guid& version, std::string_view extension) {
    return ChannelName{version, data, std::string(extension)}.to_string();
}

std::string lightcuts_result_channel_name() {
    return create_channel_name(kLightcutsDataGuid, kLightcutsVersionGuid, kLightcutsExtension);
}

std::string scene_channel_name(const Guid& scene_guid) {
    return create_channel_name(scene_guid, kSceneFormatVersionGuid, kSceneExtension);
}

std::string geometry_channel_name(const Guid& scene_guid) {
    return create_channel_name(scene_guid, kSceneFormatVersionGuid, kGeometryExtension);
}

}  // namespace lc
