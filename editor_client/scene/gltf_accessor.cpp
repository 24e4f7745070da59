// Accessor checks in the order a broken file is best told about: does the
// accessor exist, is it of a type its use takes, do its bufferView and buffer
// exist, then do its bytes lie inside them.
#include "editor_client/scene/gltf_accessor.h"

#include <cmath>
#include <cstring>

#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

namespace tg = tinygltf;

const char* type_name(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
    }
    return "unknown type";
}

int component_count(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
        case TINYGLTF_TYPE_MAT2:
            return 4;
        case TINYGLTF_TYPE_MAT3:
            return 9;
        case TINYGLTF_TYPE_MAT4:
            return 16;
    }
    return 0;
}

const char* component_type_name(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_INT:
            return "INT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return "FLOAT";
    }
    return "unknown component type";
}

int component_size(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
    }
    return 0;
}

bool is_normalized_unsigned(const tg::Accessor& a) {
    const int ct = a.componentType;
    return a.normalized &&
           (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}

// "accessor 3 (mesh 0 primitive 0 POSITION)"
std::string accessor_name(int index, const std::string& what) {
    return "accessor " + std::to_string(index) + " (" + what + ")";
}

// The accessor's bufferView, checked to lie inside its buffer; its bytes in `bytes`.
Result<const tg::BufferView*> checked_view(const tg::Model& model, const tg::Accessor& acc,
                                           const std::string& name, const uint8_t*& bytes) {
    if (acc.bufferView < 0 || acc.bufferView >= static_cast<int>(model.bufferViews.size())) {
        return make_error(name + " has bufferView " + std::to_string(acc.bufferView) +
                          ", which does not exist");
    }
    const tg::BufferView& view = model.bufferViews[size_t(acc.bufferView)];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size())) {
        return make_error("bufferView " + std::to_string(acc.bufferView) + " has buffer " +
                          std::to_string(view.buffer) + ", which does not exist");
    }
    const tg::Buffer& buffer = model.buffers[size_t(view.buffer)];
    if (!byte_range_fits(view.byteOffset, view.byteLength, buffer.data.size())) {
        return make_error("bufferView " + std::to_string(acc.bufferView) + " (offset " +
                          std::to_string(view.byteOffset) + ", length " + std::to_string(view.byteLength) +
                          ") lies outside buffer " + std::to_string(view.buffer) + ", which has " +
                          std::to_string(buffer.data.size()) + " bytes");
    }
    bytes = buffer.data.data() + view.byteOffset;
    return &view;
}

// The distance between elements: byteStride, or one element when it is 0.
Result<size_t> checked_stride(const tg::Accessor& acc, const tg::BufferView& view, const std::string& name) {
    const int csize = component_size(acc.componentType);
    const int ccount = component_count(acc.type);
    if (csize == 0 || ccount == 0) return make_error(name + " has an unknown type or component type");
    const size_t element = size_t(csize) * size_t(ccount);
    const size_t stride = view.byteStride != 0 ? view.byteStride : element;
    if (stride < element) {
        return make_error(name + ": byteStride " + std::to_string(stride) + " is smaller than one element (" +
                          std::to_string(element) + " bytes)");
    }
    return stride;
}

// The last element ends inside the view; written so that no sum overflows.
Status check_elements_fit(const tg::Accessor& acc, const tg::BufferView& view, size_t stride,
                          const std::string& name) {
    if (acc.count == 0) return Ok{};
    const size_t element = size_t(component_size(acc.componentType)) * size_t(component_count(acc.type));
    const size_t limit = view.byteLength;
    bool fits = acc.byteOffset <= limit && element <= limit - acc.byteOffset;
    if (fits) fits = (acc.count - 1) <= (limit - acc.byteOffset - element) / stride;
    if (fits) return Ok{};
    return make_error(name + ": " + std::to_string(acc.count) + " elements at offset " +
                      std::to_string(acc.byteOffset) + " with stride " + std::to_string(stride) +
                      " do not fit in bufferView " + std::to_string(acc.bufferView) + " (" +
                      std::to_string(view.byteLength) + " bytes)");
}

Error non_finite(int index, const std::string& what, size_t element) {
    return make_error(accessor_name(index, what) + " has a non-finite value at element " +
                      std::to_string(element));
}

// `Vec` elements of `N` floats each, every one finite.
template <typename Vec, int N>
Result<std::vector<Vec>> read_floats(const tg::Model& model, int index, const std::string& what,
                                     const char* expected, GltfAccessorFilter accepts) {
    Result<GltfAccessorView> view = view_gltf_accessor(model, index, what, expected, accepts);
    if (!view) return view.failure();
    std::vector<Vec> out(view->count);
    for (size_t i = 0; i < view->count; ++i) {
        for (int c = 0; c < N; ++c) {
            const float v = normalized_component(*view, i, c);
            if (!std::isfinite(v)) return non_finite(index, what, i);
            out[i][c] = v;
        }
    }
    return out;
}

uint32_t index_at(const GltfAccessorView& view, size_t i) {
    const uint8_t* p = view.element(i);
    if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return p[0];
    if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t s;
        std::memcpy(&s, p, sizeof s);
        return s;
    }
    uint32_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

}  // namespace

bool is_vec3_float(const tg::Accessor& a) {
    return a.type == TINYGLTF_TYPE_VEC3 && a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

bool is_vec4_float(const tg::Accessor& a) {
    return a.type == TINYGLTF_TYPE_VEC4 && a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

bool is_uv(const tg::Accessor& a) {
    return a.type == TINYGLTF_TYPE_VEC2 &&
           (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || is_normalized_unsigned(a));
}

bool is_color(const tg::Accessor& a) {
    return (a.type == TINYGLTF_TYPE_VEC3 || a.type == TINYGLTF_TYPE_VEC4) &&
           (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || is_normalized_unsigned(a));
}

bool is_index(const tg::Accessor& a) {
    const int ct = a.componentType;
    return a.type == TINYGLTF_TYPE_SCALAR &&
           (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
            ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
}

bool byte_range_fits(size_t offset, size_t length, size_t size) {
    return offset <= size && length <= size - offset;
}

Result<GltfAccessorView> view_gltf_accessor(const tg::Model& model, int index, const std::string& what,
                                            const char* expected, GltfAccessorFilter accepts) {
    if (index < 0 || index >= static_cast<int>(model.accessors.size())) {
        return make_error(what + " uses accessor " + std::to_string(index) +
                          ", which does not exist (the file has " + std::to_string(model.accessors.size()) +
                          " accessors)");
    }
    const tg::Accessor& acc = model.accessors[size_t(index)];
    const std::string name = accessor_name(index, what);
    if (!accepts(acc)) {
        return make_error(name + " is " + type_name(acc.type) + " " + component_type_name(acc.componentType) +
                          (acc.normalized ? " normalized" : "") + ", expected " + expected);
    }
    if (acc.sparse.isSparse) return make_error(name + " is sparse; sparse accessors are not supported");
    const uint8_t* view_bytes = nullptr;
    Result<const tg::BufferView*> view = checked_view(model, acc, name, view_bytes);
    if (!view) return view.failure();
    Result<size_t> stride = checked_stride(acc, **view, name);
    if (!stride) return stride.failure();
    LC_RETURN_IF_ERROR(check_elements_fit(acc, **view, *stride, name));
    GltfAccessorView out;
    out.base = view_bytes + acc.byteOffset;
    out.stride = *stride;
    out.count = acc.count;
    out.component_type = acc.componentType;
    out.type = acc.type;
    out.normalized = acc.normalized;
    return out;
}

float normalized_component(const GltfAccessorView& view, size_t i, int c) {
    const uint8_t* p = view.element(i);
    if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return float(p[c]) / 255.0f;
    if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t u;
        std::memcpy(&u, p + 2 * c, sizeof u);
        return float(u) / 65535.0f;
    }
    float v;
    std::memcpy(&v, p + 4 * c, sizeof v);
    return v;
}

Result<std::vector<glm::vec3>> read_gltf_vec3(const tg::Model& model, int index, const std::string& what) {
    return read_floats<glm::vec3, 3>(model, index, what, "VEC3 FLOAT", &is_vec3_float);
}

Result<std::vector<glm::vec4>> read_gltf_vec4(const tg::Model& model, int index, const std::string& what) {
    return read_floats<glm::vec4, 4>(model, index, what, "VEC4 FLOAT", &is_vec4_float);
}

Result<std::vector<glm::vec2>> read_gltf_uvs(const tg::Model& model, int index, const std::string& what) {
    return read_floats<glm::vec2, 2>(model, index, what,
                                     "VEC2 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT", &is_uv);
}

Result<std::vector<uint32_t>> read_gltf_indices(const tg::Model& model, int index, const std::string& what,
                                                size_t vertex_count) {
    Result<GltfAccessorView> view =
        view_gltf_accessor(model, index, what, "SCALAR UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT", &is_index);
    if (!view) return view.failure();
    std::vector<uint32_t> out(view->count);
    for (size_t i = 0; i < view->count; ++i) {
        const uint32_t v = index_at(*view, i);
        if (v >= vertex_count) {
            return make_error(accessor_name(index, what) + ": index " + std::to_string(v) + " at element " +
                              std::to_string(i) + " is out of range of the " + std::to_string(vertex_count) +
                              " vertices");
        }
        out[i] = v;
    }
    return out;
}

}  // namespace lc::client
