#pragma once
// A glTF's node graph, scenes and KHR_lights_punctual lights as the loader
// reads them, in flat arrays: a million-light file is a million nodes and
// lights, and per-node objects (tinygltf's Node, its Value extras) cost
// kilobytes each. Filled by the simdjson reader (gltf_node_reader.h) or from
// tinygltf's model; the loader validates it the same way either way.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "lightcuts/guid.h"

namespace lc::client {

// An `extras` boolean we read: absent, a boolean, or something else (warned about).
enum class ExtrasFlag : uint8_t { kAbsent, kFalse, kTrue, kNotBoolean };

// A node's KHR_lights_punctual extension: absent, malformed (no numeric
// 'light'), or the 'light' number as written (checked by the loader).
enum class LightReference : uint8_t { kNone, kMalformed, kNumber };

// A number array property: `count` numbers from GltfNodeTable::numbers.
struct NumberRange {
    uint32_t first = 0;
    uint32_t count = 0;
};

// A string from GltfNodeTable::text.
struct TextRange {
    uint32_t first = 0;
    uint32_t length = 0;
};

struct GltfNode {
    int32_t mesh = -1;
    int32_t camera = -1;
    uint32_t first_child = 0;  // into GltfNodeTable::children
    uint32_t child_count = 0;
    // A node with a matrix has no T/R/S (tinygltf reads them only without one).
    NumberRange matrix, translation, rotation, scale;
    LightReference light = LightReference::kNone;
    ExtrasFlag classic = ExtrasFlag::kAbsent;
    // extras.lightcuts_guid: absent, a GUID, or present but not a GUID.
    enum class GuidExtras : uint8_t { kAbsent, kGuid, kInvalid } guid_extras = GuidExtras::kAbsent;
    double light_number = 0.0;
    Guid guid;
    TextRange name;  // kept for nodes with a camera only (a camera may take its node's name)
};

struct GltfPunctualLight {
    TextRange name;
    TextRange type;
    uint8_t color_count = 0;  // 0: absent (white); only 3 is valid
    ExtrasFlag classic = ExtrasFlag::kAbsent;
    double color[3] = {1.0, 1.0, 1.0};
    double intensity = 1.0;
    double range = 0.0;
    double inner_cone_angle = 0.0;
    // tinygltf's default, pi/4 as it writes it: both readers give the same float.
    double outer_cone_angle = 0.7853981634;
};

struct GltfNodeTable {
    std::vector<GltfNode> nodes;
    std::vector<int32_t> children;
    std::vector<double> numbers;
    std::vector<char> text;
    std::vector<GltfPunctualLight> lights;
    // Each scene's root nodes, from scene_roots.
    std::vector<NumberRange> scenes;
    std::vector<int32_t> scene_roots;

    std::span<const int32_t> children_of(const GltfNode& node) const {
        return {children.data() + node.first_child, node.child_count};
    }
    std::span<const int32_t> roots_of(size_t scene) const {
        return {scene_roots.data() + scenes[scene].first, scenes[scene].count};
    }
    std::span<const double> values(NumberRange range) const {
        return {numbers.data() + range.first, range.count};
    }
    std::string_view string(TextRange range) const {
        return {text.data() + range.first, range.length};
    }
    NumberRange add_numbers(std::span<const double> values) {
        const NumberRange range{uint32_t(numbers.size()), uint32_t(values.size())};
        numbers.insert(numbers.end(), values.begin(), values.end());
        return range;
    }
    TextRange add_text(std::string_view value) {
        const TextRange range{uint32_t(text.size()), uint32_t(value.size())};
        text.insert(text.end(), value.begin(), value.end());
        return range;
    }
};

}  // namespace lc::client
