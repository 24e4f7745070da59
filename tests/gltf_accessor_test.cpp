// The checked accessor view (gltf_accessor.h) on hand-made tinygltf models:
// well-formed accessors read their values (strides, normalised integers,
// index widths), and hostile ones (missing accessors, views and buffers,
// offsets past the end, counts that overflow, strides shorter than an
// element, wrong types, sparse) give an error naming the problem, before a
// byte outside the buffer is read.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "editor_client/scene/gltf_accessor.h"

namespace lc::client {
namespace {

namespace tg = tinygltf;
using ::testing::HasSubstr;

// One buffer holding `bytes`, one view over all of it (byteStride `stride`),
// and one accessor of `count` elements at `offset` in that view.
tg::Model model_of(std::vector<uint8_t> bytes, int type, int component_type, size_t count, size_t offset = 0,
                   size_t stride = 0) {
    tg::Model model;
    tg::Buffer buffer;
    buffer.data = std::move(bytes);
    tg::BufferView view;
    view.buffer = 0;
    view.byteLength = buffer.data.size();
    view.byteStride = stride;
    tg::Accessor accessor;
    accessor.bufferView = 0;
    accessor.byteOffset = offset;
    accessor.count = count;
    accessor.type = type;
    accessor.componentType = component_type;
    model.buffers.push_back(std::move(buffer));
    model.bufferViews.push_back(view);
    model.accessors.push_back(accessor);
    return model;
}

template <typename T>
std::vector<uint8_t> bytes_of(const std::vector<T>& values) {
    std::vector<uint8_t> bytes(values.size() * sizeof(T));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

tg::Model vec3_model(size_t count, size_t offset = 0, size_t stride = 0) {
    return model_of(bytes_of(std::vector<float>{0, 1, 2, 3, 4, 5, 6, 7, 8}), TINYGLTF_TYPE_VEC3,
                    TINYGLTF_COMPONENT_TYPE_FLOAT, count, offset, stride);
}

TEST(GltfAccessor, ReadsTightlyPackedVec3) {
    Result<std::vector<glm::vec3>> read = read_gltf_vec3(vec3_model(3), 0, "positions");
    ASSERT_TRUE(read) << read.error();
    ASSERT_EQ(read->size(), 3u);
    EXPECT_EQ((*read)[0], glm::vec3(0, 1, 2));
    EXPECT_EQ((*read)[2], glm::vec3(6, 7, 8));
}

TEST(GltfAccessor, HonoursOffsetAndStride) {
    // Elements at bytes 4 and 4 + 20: floats 1..3 and 6..8 of the nine.
    Result<std::vector<glm::vec3>> read = read_gltf_vec3(vec3_model(2, 4, 20), 0, "positions");
    ASSERT_TRUE(read) << read.error();
    EXPECT_EQ((*read)[0], glm::vec3(1, 2, 3));
    EXPECT_EQ((*read)[1], glm::vec3(6, 7, 8));
}

TEST(GltfAccessor, DecodesNormalizedUnsignedUvs) {
    tg::Model bytes =
        model_of({0, 255, 51, 102}, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 2);
    bytes.accessors[0].normalized = true;
    Result<std::vector<glm::vec2>> uv8 = read_gltf_uvs(bytes, 0, "uv");
    ASSERT_TRUE(uv8) << uv8.error();
    EXPECT_EQ((*uv8)[0], glm::vec2(0.0f, 1.0f));
    EXPECT_FLOAT_EQ((*uv8)[1].x, 0.2f);
    EXPECT_FLOAT_EQ((*uv8)[1].y, 0.4f);

    tg::Model shorts = model_of(bytes_of(std::vector<uint16_t>{65535, 0}), TINYGLTF_TYPE_VEC2,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 1);
    shorts.accessors[0].normalized = true;
    Result<std::vector<glm::vec2>> uv16 = read_gltf_uvs(shorts, 0, "uv");
    ASSERT_TRUE(uv16) << uv16.error();
    EXPECT_EQ((*uv16)[0], glm::vec2(1.0f, 0.0f));
}

TEST(GltfAccessor, ReadsEveryIndexWidth) {
    const tg::Model bytes =
        model_of({2, 0, 1}, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 3);
    const tg::Model shorts = model_of(bytes_of(std::vector<uint16_t>{2, 0, 1}), TINYGLTF_TYPE_SCALAR,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 3);
    const tg::Model ints = model_of(bytes_of(std::vector<uint32_t>{2, 0, 1}), TINYGLTF_TYPE_SCALAR,
                                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, 3);
    for (const tg::Model* model : {&bytes, &shorts, &ints}) {
        Result<std::vector<uint32_t>> read = read_gltf_indices(*model, 0, "indices", 3);
        ASSERT_TRUE(read) << read.error();
        EXPECT_EQ(*read, (std::vector<uint32_t>{2, 0, 1}));
    }
}

TEST(GltfAccessor, RefusesAnIndexPastTheVertices) {
    const tg::Model model =
        model_of({0, 1, 3}, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 3);
    Result<std::vector<uint32_t>> read = read_gltf_indices(model, 0, "indices", 3);
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error(), "accessor 0 (indices): index 3 at element 2 is out of range of the 3 vertices");
}

TEST(GltfAccessor, RefusesAMissingAccessor) {
    for (int index : {-1, 1, std::numeric_limits<int>::max()}) {
        Result<std::vector<glm::vec3>> read = read_gltf_vec3(vec3_model(3), index, "mesh 0 POSITION");
        ASSERT_FALSE(read);
        EXPECT_EQ(read.error(), "mesh 0 POSITION uses accessor " + std::to_string(index) +
                                    ", which does not exist (the file has 1 accessors)");
    }
}

TEST(GltfAccessor, RefusesAWrongTypeBeforeAnyRangeCheck) {
    tg::Model model = vec3_model(1000);  // its extent is wrong too: the type is reported
    model.accessors[0].type = TINYGLTF_TYPE_VEC2;
    Result<std::vector<glm::vec3>> read = read_gltf_vec3(model, 0, "positions");
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error(), "accessor 0 (positions) is VEC2 FLOAT, expected VEC3 FLOAT");

    tg::Model unnormalized = model_of({0, 255}, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 1);
    Result<std::vector<glm::vec2>> uv = read_gltf_uvs(unnormalized, 0, "uv");
    ASSERT_FALSE(uv);
    EXPECT_THAT(uv.error(), HasSubstr("is VEC2 UNSIGNED_BYTE, expected VEC2 FLOAT or normalized"));

    tg::Model signed_indices = model_of({0, 1, 2}, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_BYTE, 3);
    Result<std::vector<uint32_t>> indices = read_gltf_indices(signed_indices, 0, "indices", 3);
    ASSERT_FALSE(indices);
    EXPECT_THAT(indices.error(), HasSubstr("is SCALAR BYTE, expected SCALAR UNSIGNED_BYTE"));
}

TEST(GltfAccessor, RefusesAnUnknownComponentType) {
    tg::Model model = vec3_model(1);
    model.accessors[0].componentType = 1234;
    Result<GltfAccessorView> view =
        view_gltf_accessor(model, 0, "data", "anything", [](const tg::Accessor&) { return true; });
    ASSERT_FALSE(view);
    EXPECT_EQ(view.error(), "accessor 0 (data) has an unknown type or component type");
}

TEST(GltfAccessor, RefusesSparseAccessors) {
    tg::Model model = vec3_model(3);
    model.accessors[0].sparse.isSparse = true;
    Result<std::vector<glm::vec3>> read = read_gltf_vec3(model, 0, "positions");
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error(), "accessor 0 (positions) is sparse; sparse accessors are not supported");
}

TEST(GltfAccessor, RefusesMissingViewsAndBuffers) {
    tg::Model no_view = vec3_model(3);
    no_view.accessors[0].bufferView = 7;
    Result<std::vector<glm::vec3>> read = read_gltf_vec3(no_view, 0, "positions");
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error(), "accessor 0 (positions) has bufferView 7, which does not exist");

    tg::Model no_buffer = vec3_model(3);
    no_buffer.bufferViews[0].buffer = -2;
    read = read_gltf_vec3(no_buffer, 0, "positions");
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error(), "bufferView 0 has buffer -2, which does not exist");
}

TEST(GltfAccessor, RefusesAViewOutsideItsBuffer) {
    tg::Model model = vec3_model(1);
    model.bufferViews[0].byteOffset = std::numeric_limits<size_t>::max() - 8;  // offset + length wraps
    Result<std::vector<glm::vec3>> read = read_gltf_vec3(model, 0, "positions");
    ASSERT_FALSE(read);
    EXPECT_THAT(read.error(), HasSubstr("bufferView 0 (offset 18446744073709551607, length 36) lies outside "
                                        "buffer 0, which has 36 bytes"));
}

TEST(GltfAccessor, RefusesAnOffsetPastTheView) {
    Result<std::vector<glm::vec3>> read = read_gltf_vec3(vec3_model(1, 28), 0, "positions");
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error(),
              "accessor 0 (positions): 1 elements at offset 28 with stride 12 do not fit in bufferView 0 (36 "
              "bytes)");
    read = read_gltf_vec3(vec3_model(1, std::numeric_limits<size_t>::max()), 0, "positions");
    ASSERT_FALSE(read);
    EXPECT_THAT(read.error(), HasSubstr("do not fit in bufferView 0"));
}

TEST(GltfAccessor, RefusesCountsThatOverflow) {
    // count * stride wraps around to a small number in 64 bits: still refused.
    for (size_t count : {size_t(4), std::numeric_limits<size_t>::max(), (size_t(1) << 62) + 1}) {
        Result<std::vector<glm::vec3>> read = read_gltf_vec3(vec3_model(count), 0, "positions");
        ASSERT_FALSE(read) << count;
        EXPECT_THAT(read.error(), HasSubstr(std::to_string(count) + " elements at offset 0 with stride 12"));
    }
}

TEST(GltfAccessor, RefusesAStrideShorterThanAnElement) {
    Result<std::vector<glm::vec3>> read = read_gltf_vec3(vec3_model(2, 0, 8), 0, "positions");
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error(), "accessor 0 (positions): byteStride 8 is smaller than one element (12 bytes)");
}

TEST(GltfAccessor, RefusesNonFiniteFloats) {
    std::vector<float> values{0, 1, 2, 3, std::numeric_limits<float>::quiet_NaN(), 5};
    const tg::Model model = model_of(bytes_of(values), TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, 2);
    Result<std::vector<glm::vec3>> read = read_gltf_vec3(model, 0, "normals");
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error(), "accessor 0 (normals) has a non-finite value at element 1");
}

TEST(GltfAccessor, AnEmptyAccessorNeedsNoBytes) {
    tg::Model model = vec3_model(0, 36);  // at the view's very end
    Result<GltfAccessorView> view = view_gltf_accessor(model, 0, "positions", "VEC3 FLOAT", &is_vec3_float);
    ASSERT_TRUE(view) << view.error();
    EXPECT_EQ(view->count, 0u);
    EXPECT_EQ(view->stride, 12u);
}

}  // namespace
}  // namespace lc::client
