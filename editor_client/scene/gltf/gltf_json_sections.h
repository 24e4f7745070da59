#pragma once
// One pass over a glTF's JSON text that finds the three arrays the node
// reader takes (top-level `nodes` and `scenes`, and `extensions`'
// KHR_lights_punctual `lights`) and hands their elements on in runs of about
// `run_bytes`, without parsing them: a parser then indexes one run at a time,
// never the whole document, and the text behind the scan can be released.
//
// The scan checks the top level's grammar and where each element ends
// (strings, escapes, nesting); it leaves the values to parsers: each run goes
// to the node reader's parser, and the rest of the document (the remainder,
// those arrays emptied) to tinygltf. A document it cannot split so (not an
// object at the top, an escaped key, a section twice or not an array, a
// stray byte between values) gives nullopt, and the caller reads the whole
// file with tinygltf.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace lc::client {

enum class GltfSection : uint8_t { kNodes, kScenes, kLights };

struct GltfSectionHandlers {
    // Whole elements of one section as written, with the commas between
    // them; false stops the scan (the document is then refused).
    std::function<bool(GltfSection, std::string_view elements)> on_elements;
    // The scan will not read the text before this offset again.
    std::function<void(size_t offset)> on_consumed;
};

// The remainder: `json` with each section's array replaced by [].
std::optional<std::string> split_gltf_sections(std::string_view json, size_t run_bytes,
                                               const GltfSectionHandlers& handlers);

}  // namespace lc::client
