#include "editor_client/scene/gltf_model_nodes.h"

#include <algorithm>
#include <optional>
#include <string>

#include "editor_client/scene/gltf_loader.h"

namespace lc::client {
namespace {

namespace tg = tinygltf;

constexpr const char* kLightsExtension = "KHR_lights_punctual";

// A node's or light's extras.lightcuts_classic as tinygltf parsed it.
ExtrasFlag classic_flag_of(const tg::Value& extras) {
    if (!extras.IsObject() || !extras.Has(kClassicExtrasKey)) return ExtrasFlag::kAbsent;
    const tg::Value& v = extras.Get(kClassicExtrasKey);
    if (!v.IsBool()) return ExtrasFlag::kNotBoolean;
    return v.Get<bool>() ? ExtrasFlag::kTrue : ExtrasFlag::kFalse;
}

// The node's KHR_lights_punctual reference and its extras (classic flag, GUID).
void read_light_fields(const tg::Node& in, GltfNode& node) {
    auto extension = in.extensions.find(kLightsExtension);
    if (extension != in.extensions.end()) {
        const tg::Value& e = extension->second;
        const bool numbered = e.IsObject() && e.Has("light") && e.Get("light").IsNumber();
        node.light = numbered ? LightReference::kNumber : LightReference::kMalformed;
        if (numbered) node.light_number = e.Get("light").GetNumberAsDouble();
    }
    node.classic = classic_flag_of(in.extras);
    if (in.extras.IsObject() && in.extras.Has(kGuidExtrasKey)) {
        const tg::Value& v = in.extras.Get(kGuidExtrasKey);
        std::optional<Guid> guid = v.IsString() ? Guid::parse(v.Get<std::string>()) : std::nullopt;
        node.guid_extras = guid ? GltfNode::GuidExtras::kGuid : GltfNode::GuidExtras::kInvalid;
        if (guid) node.guid = *guid;
    }
}

GltfNode node_from(const tg::Node& in, GltfNodeTable& table) {
    GltfNode node;
    node.mesh = in.mesh;
    node.camera = in.camera;
    node.first_child = uint32_t(table.children.size());
    node.child_count = uint32_t(in.children.size());
    table.children.insert(table.children.end(), in.children.begin(), in.children.end());
    node.matrix = table.add_numbers(in.matrix);
    node.translation = table.add_numbers(in.translation);
    node.rotation = table.add_numbers(in.rotation);
    node.scale = table.add_numbers(in.scale);
    read_light_fields(in, node);
    if (in.camera >= 0) node.name = table.add_text(in.name);
    return node;
}

GltfPunctualLight light_from(const tg::Light& in, GltfNodeTable& table) {
    GltfPunctualLight light;
    light.name = table.add_text(in.name);
    light.type = table.add_text(in.type);
    // Only 3 is valid; a longer list keeps a count that says it is not.
    light.color_count = uint8_t(std::min<size_t>(in.color.size(), 255));
    if (in.color.size() == 3) std::copy(in.color.begin(), in.color.end(), light.color);
    light.intensity = in.intensity;
    light.range = in.range;
    light.inner_cone_angle = in.spot.innerConeAngle;
    light.outer_cone_angle = in.spot.outerConeAngle;
    light.classic = classic_flag_of(in.extras);
    return light;
}

}  // namespace

GltfNodeTable node_table_from(const tg::Model& model) {
    GltfNodeTable table;
    table.nodes.reserve(model.nodes.size());
    for (const tg::Node& in : model.nodes) table.nodes.push_back(node_from(in, table));
    for (const tg::Scene& scene : model.scenes) {
        table.scenes.push_back({uint32_t(table.scene_roots.size()), uint32_t(scene.nodes.size())});
        table.scene_roots.insert(table.scene_roots.end(), scene.nodes.begin(), scene.nodes.end());
    }
    table.lights.reserve(model.lights.size());
    for (const tg::Light& in : model.lights) table.lights.push_back(light_from(in, table));
    return table;
}

}  // namespace lc::client
