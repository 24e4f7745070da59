#pragma once
// A checked view over a glTF accessor's bytes. Before a byte is read, the
// accessor's type is checked against what its use accepts, then its
// bufferView and buffer exist, the view lies inside its buffer, the stride
// holds one element and the last element ends inside the view (no overflow
// for any count or offset). Sparse accessors are refused. Errors name the
// accessor and its use, without the file's name (the loader adds it).
#include <tiny_gltf.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "lightcuts/result.h"

namespace lc::client {

struct GltfAccessorView {
    const uint8_t* base = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;  // TINYGLTF_COMPONENT_TYPE_*
    int type = 0;            // TINYGLTF_TYPE_*
    bool normalized = false;

    const uint8_t* element(size_t i) const { return base + i * stride; }
};

// Which accessors a use takes (type, component type, normalisation).
using GltfAccessorFilter = bool (*)(const tinygltf::Accessor&);
bool is_vec3_float(const tinygltf::Accessor& a);
bool is_vec4_float(const tinygltf::Accessor& a);
// VEC2 FLOAT, or normalized UNSIGNED_BYTE/UNSIGNED_SHORT.
bool is_uv(const tinygltf::Accessor& a);
// VEC3/VEC4 FLOAT, or normalized UNSIGNED_BYTE/UNSIGNED_SHORT.
bool is_color(const tinygltf::Accessor& a);
// SCALAR UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT.
bool is_index(const tinygltf::Accessor& a);

// [offset, offset + length) fits inside `size` bytes, without overflow.
bool byte_range_fits(size_t offset, size_t length, size_t size);

// Accessor `index` of `model` for `what` ("mesh 0 primitive 1 POSITION").
// `expected` names the accepted types for the message; `accepts` checks them
// before any range check, so a wrong type is reported as such.
Result<GltfAccessorView> view_gltf_accessor(const tinygltf::Model& model, int index, const std::string& what,
                                            const char* expected, GltfAccessorFilter accepts);

// Component `c` of element `i` as a float: FLOAT as stored, normalized
// UNSIGNED_BYTE/UNSIGNED_SHORT divided by their largest value.
float normalized_component(const GltfAccessorView& view, size_t i, int c);

// Whole accessors, each value checked: finite floats, indices below `vertex_count`.
Result<std::vector<glm::vec3>> read_gltf_vec3(const tinygltf::Model& model, int index,
                                              const std::string& what);
Result<std::vector<glm::vec4>> read_gltf_vec4(const tinygltf::Model& model, int index,
                                              const std::string& what);
Result<std::vector<glm::vec2>> read_gltf_uvs(const tinygltf::Model& model, int index,
                                             const std::string& what);
Result<std::vector<uint32_t>> read_gltf_indices(const tinygltf::Model& model, int index,
                                                const std::string& what, size_t vertex_count);

}  // namespace lc::client
