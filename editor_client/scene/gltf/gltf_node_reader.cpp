// simdjson On-Demand over a glTF's nodes, scenes and punctual lights. Every
// value of those arrays is either read with its type checked or refused
// (nullopt): On-Demand does not validate what it skips, and what the reader
// takes out of the document tinygltf never sees.
#include "editor_client/scene/gltf/gltf_node_reader.h"

#include <simdjson.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/gltf_json_sections.h"

namespace lc::client {
namespace {

namespace sj = simdjson::ondemand;
using simdjson::SUCCESS;

// tinygltf's JSON (nlohmann) keeps integer tokens as 64-bit integers and
// converts them when asked for a double: "-0" is +0 there, and here.
bool read_number(sj::value value, double& out) {
    sj::number number;
    if (value.get_number().get(number) != SUCCESS) return false;
    switch (number.get_number_type()) {
        case sj::number_type::signed_integer:
            out = double(number.get_int64());
            return true;
        case sj::number_type::unsigned_integer:
            out = double(number.get_uint64());
            return true;
        case sj::number_type::floating_point_number:
            out = number.get_double();
            return true;
    }
    return false;
}

// An integer token that fits an int (tinygltf truncates wider ones; we refuse them).
bool read_int(sj::value value, int32_t& out) {
    sj::number number;
    if (value.get_number().get(number) != SUCCESS) return false;
    if (number.get_number_type() != sj::number_type::signed_integer &&
        number.get_number_type() != sj::number_type::unsigned_integer) {
        return false;
    }
    if (!number.is_int64()) return false;
    const int64_t v = number.get_int64();
    if (v < std::numeric_limits<int32_t>::min() || v > std::numeric_limits<int32_t>::max()) {
        return false;
    }
    out = int32_t(v);
    return true;
}

bool read_numbers(sj::value value, GltfNodeTable& table, NumberRange& out) {
    sj::array array;
    if (value.get_array().get(array) != SUCCESS) return false;
    out.first = uint32_t(table.numbers.size());
    for (auto element : array) {
        sj::value v;
        double number = 0.0;
        if (element.get(v) != SUCCESS || !read_number(v, number)) return false;
        table.numbers.push_back(number);
    }
    out.count = uint32_t(table.numbers.size() - out.first);
    return true;
}

bool read_ints(sj::value value, std::vector<int32_t>& pool, NumberRange& out) {
    sj::array array;
    if (value.get_array().get(array) != SUCCESS) return false;
    out.first = uint32_t(pool.size());
    for (auto element : array) {
        sj::value v;
        int32_t number = 0;
        if (element.get(v) != SUCCESS || !read_int(v, number)) return false;
        pool.push_back(number);
    }
    out.count = uint32_t(pool.size() - out.first);
    return true;
}

bool read_string(sj::value value, std::string_view& out) {
    return value.get_string().get(out) == SUCCESS;
}

// A key or string as written, when it has no escapes (refused otherwise). It
// points into the document: unescaping every key of a million nodes would
// copy hundreds of megabytes into simdjson's string buffer.
bool plain_text(sj::raw_json_string raw, std::string_view& out) {
    const char* text = raw.raw();
    size_t length = 0;
    while (text[length] != '"') {
        if (text[length] == '\\') return false;
        ++length;
    }
    out = std::string_view(text, length);
    return true;
}

bool read_plain_string(sj::value value, std::string_view& out) {
    sj::raw_json_string raw;
    return value.get_raw_json_string().get(raw) == SUCCESS && plain_text(raw, out);
}

bool read_key(sj::field& field, std::string_view& key) {
    return plain_text(field.key(), key);
}

bool read_classic(sj::value value, ExtrasFlag& out) {
    bool flag = false;
    if (value.get_bool().get(flag) != SUCCESS) return false;  // the loader warns: tinygltf's path
    out = flag ? ExtrasFlag::kTrue : ExtrasFlag::kFalse;
    return true;
}

// Iterates an object's fields, handing each key and value to `read`, which
// returns false for a field it does not take.
template <typename Read>
bool for_each_field(sj::value value, Read&& read) {
    sj::object object;
    if (value.get_object().get(object) != SUCCESS) return false;
    for (auto field_result : object) {
        sj::field field;
        std::string_view key;
        if (std::move(field_result).get(field) != SUCCESS || !read_key(field, key)) return false;
        if (!read(key, field.value())) return false;
    }
    return true;
}

bool read_node(sj::value value, GltfNodeTable& table, GltfNode& node) {
    bool has_matrix = false;
    std::string_view name;
    const bool ok = for_each_field(value, [&](std::string_view key, sj::value v) {
        if (key == "name") return read_string(v, name);
        if (key == "mesh") return read_int(v, node.mesh);
        if (key == "camera") return read_int(v, node.camera);
        if (key == "children") {
            NumberRange children;
            if (!read_ints(v, table.children, children)) return false;
            node.first_child = children.first;
            node.child_count = children.count;
            return true;
        }
        if (key == "matrix") {
            has_matrix = true;
            return read_numbers(v, table, node.matrix);
        }
        if (key == "translation") return read_numbers(v, table, node.translation);
        if (key == "rotation") return read_numbers(v, table, node.rotation);
        if (key == "scale") return read_numbers(v, table, node.scale);
        if (key == "extensions") {
            return for_each_field(v, [&](std::string_view extension, sj::value e) {
                if (extension != "KHR_lights_punctual") return false;
                node.light = LightReference::kMalformed;
                return for_each_field(e, [&](std::string_view field, sj::value index) {
                    int32_t light = -1;
                    if (field != "light" || !read_int(index, light) || light < 0) return false;
                    node.light = LightReference::kNumber;
                    node.light_number = double(light);
                    return true;
                });
            });
        }
        if (key == "extras") {
            return for_each_field(v, [&](std::string_view extra, sj::value e) {
                if (extra == kClassicExtrasKey) return read_classic(e, node.classic);
                if (extra != kGuidExtrasKey) return false;
                std::string_view text;
                if (!read_plain_string(e, text)) return false;
                const std::optional<Guid> guid = Guid::parse(text);
                node.guid_extras = guid ? GltfNode::GuidExtras::kGuid : GltfNode::GuidExtras::kInvalid;
                if (guid) node.guid = *guid;
                return true;
            });
        }
        return false;
    });
    if (!ok) return false;
    // tinygltf reads T/R/S only when there is no matrix.
    if (has_matrix) node.translation = node.rotation = node.scale = NumberRange{};
    if (node.camera >= 0) node.name = table.add_text(name);
    return true;
}

bool read_light(sj::value value, GltfNodeTable& table, GltfPunctualLight& light) {
    std::string_view name;
    std::string_view type;
    bool has_type = false;
    bool has_spot = false;
    double inner = light.inner_cone_angle;
    double outer = light.outer_cone_angle;
    const bool ok = for_each_field(value, [&](std::string_view key, sj::value v) {
        if (key == "name") return read_string(v, name);
        if (key == "type") return has_type = read_string(v, type);
        if (key == "intensity") return read_number(v, light.intensity);
        if (key == "range") return read_number(v, light.range);
        if (key == "color") {
            NumberRange color;
            if (!read_numbers(v, table, color) || color.count != 3) return false;
            std::copy_n(table.numbers.begin() + color.first, 3, light.color);
            table.numbers.resize(color.first);
            light.color_count = 3;
            return true;
        }
        if (key == "spot") {
            has_spot = true;
            return for_each_field(v, [&](std::string_view angle, sj::value a) {
                if (angle == "innerConeAngle") return read_number(a, inner);
                if (angle == "outerConeAngle") return read_number(a, outer);
                return false;
            });
        }
        if (key == "extras") {
            return for_each_field(v, [&](std::string_view extra, sj::value e) {
                return extra == kClassicExtrasKey && read_classic(e, light.classic);
            });
        }
        return false;
    });
    // tinygltf requires a type, and a spot object on spot lights only.
    if (!ok || !has_type || (type == "spot" && !has_spot)) return false;
    if (type == "spot") {
        light.inner_cone_angle = inner;
        light.outer_cone_angle = outer;
    }
    light.name = table.add_text(name);
    light.type = table.add_text(type);
    return true;
}

bool read_scene(sj::value value, GltfNodeTable& table, NumberRange& roots) {
    return for_each_field(value, [&](std::string_view key, sj::value v) {
        std::string_view name;
        if (key == "name") return read_string(v, name);
        return key == "nodes" && read_ints(v, table.scene_roots, roots);
    });
}

// Parses one run of a section's elements, copied between brackets into a
// buffer with simdjson's padding, with `read` on each element.
template <typename Read>
bool for_each_element(sj::parser& parser, std::vector<char>& buffer, std::string_view elements,
                      Read&& read) {
    buffer.resize(elements.size() + 2 + simdjson::SIMDJSON_PADDING);
    buffer[0] = '[';
    std::memcpy(buffer.data() + 1, elements.data(), elements.size());
    buffer[elements.size() + 1] = ']';
    sj::document doc;
    if (parser.iterate(buffer.data(), elements.size() + 2, buffer.size()).get(doc) != SUCCESS) {
        return false;
    }
    sj::array array;
    if (doc.get_array().get(array) != SUCCESS) return false;
    for (auto element : array) {
        sj::value v;
        if (element.get(v) != SUCCESS || !read(v)) return false;
    }
    // Nothing follows the array (On-Demand stops reading where we stop).
    return doc.current_location().error() == simdjson::OUT_OF_BOUNDS;
}

// How many bytes of elements the parser indexes at a time: its index is about
// four bytes per token of one run, not of the whole document.
constexpr size_t kRunBytes = size_t{1} << 20;

std::optional<GltfNodeSplit> read_json(std::string_view json, const ConsumedBytes& on_consumed) {
    sj::parser parser;
    std::vector<char> buffer;
    GltfNodeSplit split;
    GltfNodeTable& table = split.table;
    // Each element of a run read by `read` into a new entry of `entries`.
    auto append_elements = [&](std::string_view elements, auto& entries, auto&& read) {
        return for_each_element(parser, buffer, elements, [&](sj::value v) {
            typename std::remove_reference_t<decltype(entries)>::value_type entry{};
            if (!read(v, entry)) return false;
            entries.push_back(entry);
            return true;
        });
    };
    auto read_elements = [&](GltfSection section, std::string_view elements) {
        switch (section) {
            case GltfSection::kNodes:
                return append_elements(elements, table.nodes,
                                       [&](sj::value v, GltfNode& node) { return read_node(v, table, node); });
            case GltfSection::kScenes:
                return append_elements(elements, table.scenes, [&](sj::value v, NumberRange& roots) {
                    roots.first = uint32_t(table.scene_roots.size());
                    return read_scene(v, table, roots);
                });
            case GltfSection::kLights:
                return append_elements(elements, table.lights, [&](sj::value v, GltfPunctualLight& light) {
                    return read_light(v, table, light);
                });
        }
        return false;
    };
    std::optional<std::string> remainder =
        split_gltf_sections(json, kRunBytes, {read_elements, on_consumed});
    if (!remainder) return std::nullopt;
    split.remainder = std::move(*remainder);
    return split;
}

uint32_t read_u32(const uint8_t* at) {
    return uint32_t(at[0]) | uint32_t(at[1]) << 8 | uint32_t(at[2]) << 16 | uint32_t(at[3]) << 24;
}

void append_u32(std::string& out, size_t value) {
    for (int i = 0; i < 4; ++i) out += char(uint8_t(value >> (8 * i)));
}

constexpr uint32_t kGlbVersion = 2;
constexpr uint32_t kGlbChunkJson = 0x4E4F534Au;  // "JSON"
constexpr size_t kGlbHeaderBytes = 12;
constexpr size_t kGlbChunkHeaderBytes = 8;

// A .glb whose header and JSON chunk are as the specification writes them;
// the remainder is the same container around the emptied JSON, the chunks
// after it copied as they are.
std::optional<GltfNodeSplit> read_glb(std::span<const uint8_t> file, const ConsumedBytes& on_consumed) {
    constexpr size_t json_at = kGlbHeaderBytes + kGlbChunkHeaderBytes;
    if (file.size() < json_at || read_u32(&file[4]) != kGlbVersion ||
        read_u32(&file[8]) != file.size() || read_u32(&file[16]) != kGlbChunkJson) {
        return std::nullopt;
    }
    const size_t json_bytes = read_u32(&file[12]);
    if (json_bytes > file.size() - json_at) return std::nullopt;
    const std::string_view json(reinterpret_cast<const char*>(file.data()) + json_at, json_bytes);
    std::optional<GltfNodeSplit> split = read_json(json, [&](size_t offset) {
        if (on_consumed) on_consumed(json_at + offset);
    });
    if (!split) return std::nullopt;
    std::string text = std::move(split->remainder);
    while (text.size() % 4 != 0) text += ' ';
    const std::span<const uint8_t> chunks_after = file.subspan(json_at + json_bytes);
    std::string& glb = split->remainder;
    glb.reserve(json_at + text.size() + chunks_after.size());
    glb.append(reinterpret_cast<const char*>(file.data()), 8);
    append_u32(glb, json_at + text.size() + chunks_after.size());
    append_u32(glb, text.size());
    append_u32(glb, kGlbChunkJson);
    glb += text;
    glb.append(reinterpret_cast<const char*>(chunks_after.data()), chunks_after.size());
    return split;
}

}  // namespace

std::optional<GltfNodeSplit> read_gltf_nodes(std::span<const uint8_t> file,
                                             const ConsumedBytes& on_consumed) {
    if (file.size() >= 4 && std::memcmp(file.data(), "glTF", 4) == 0) return read_glb(file, on_consumed);
    return read_json(std::string_view(reinterpret_cast<const char*>(file.data()), file.size()),
                     on_consumed);
}

}  // namespace lc::client
