#pragma once
// Loads a glTF file twice, with the simdjson node reader (the default) and
// with tinygltf reading everything (the loader as it was), and expects the
// same outcome: the same scene bit for bit, or the same error, and the same
// warnings. Used by the loader's tests on every input they load, and by the
// node reader's own tests.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "editor_client/scene/gltf/gltf_loader.h"

namespace lc::test {

template <typename T>
bool same_bits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

inline void expect_same_light(const SceneLight& a, const SceneLight& b, size_t i) {
    EXPECT_EQ(a.guid, b.guid) << "light " << i;
    EXPECT_EQ(a.type, b.type) << "light " << i;
    EXPECT_TRUE(same_bits(a.position, b.position)) << "light " << i;
    EXPECT_TRUE(same_bits(a.direction, b.direction)) << "light " << i;
    EXPECT_TRUE(same_bits(a.color, b.color)) << "light " << i;
    EXPECT_TRUE(same_bits(a.intensity, b.intensity)) << "light " << i;
    EXPECT_TRUE(same_bits(a.range, b.range)) << "light " << i;
    EXPECT_TRUE(same_bits(a.inner_cone_angle, b.inner_cone_angle)) << "light " << i;
    EXPECT_TRUE(same_bits(a.outer_cone_angle, b.outer_cone_angle)) << "light " << i;
    EXPECT_EQ(a.classic, b.classic) << "light " << i;
}

inline void expect_same_scene(const Scene& a, const Scene& b) {
    EXPECT_EQ(a.guid, b.guid);
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (size_t i = 0; i < a.lights.size(); ++i) expect_same_light(a.lights[i], b.lights[i], i);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        EXPECT_TRUE(same_bits(a.meshes[i].positions, b.meshes[i].positions)) << "mesh " << i;
        EXPECT_TRUE(same_bits(a.meshes[i].normals, b.meshes[i].normals)) << "mesh " << i;
        EXPECT_TRUE(same_bits(a.meshes[i].uvs, b.meshes[i].uvs)) << "mesh " << i;
        EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices) << "mesh " << i;
        EXPECT_EQ(a.meshes[i].material, b.meshes[i].material) << "mesh " << i;
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        const Material& m = a.materials[i];
        const Material& n = b.materials[i];
        EXPECT_TRUE(same_bits(m.base_color_factor, n.base_color_factor) &&
                    same_bits(m.emissive_factor, n.emissive_factor) &&
                    same_bits(m.metallic, n.metallic) && same_bits(m.roughness, n.roughness) &&
                    m.base_color_texture == n.base_color_texture &&
                    m.metallic_roughness_texture == n.metallic_roughness_texture &&
                    m.emissive_texture == n.emissive_texture && m.casts_shadows == n.casts_shadows)
            << "material " << i;
    }
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (size_t i = 0; i < a.textures.size(); ++i) {
        EXPECT_EQ(a.textures[i].rgba8, b.textures[i].rgba8) << "texture " << i;
    }
    ASSERT_EQ(a.cameras.size(), b.cameras.size());
    for (size_t i = 0; i < a.cameras.size(); ++i) {
        EXPECT_EQ(a.cameras[i].name, b.cameras[i].name);
        EXPECT_TRUE(same_bits(a.cameras[i].eye, b.cameras[i].eye)) << "camera " << i;
        EXPECT_TRUE(same_bits(a.cameras[i].target, b.cameras[i].target)) << "camera " << i;
        EXPECT_TRUE(same_bits(a.cameras[i].up, b.cameras[i].up)) << "camera " << i;
        EXPECT_TRUE(same_bits(a.cameras[i].yfov, b.cameras[i].yfov)) << "camera " << i;
    }
    EXPECT_TRUE(same_bits(a.bounds_min, b.bounds_min));
    EXPECT_TRUE(same_bits(a.bounds_max, b.bounds_max));
}

// The fast load's result, after checking it against tinygltf's.
inline Result<Scene> load_scene_both_ways(const std::filesystem::path& path,
                                          std::vector<std::string>& warnings,
                                          client::GltfLoadOptions options = {}) {
    options.stream_nodes = false;
    std::vector<std::string> reference_warnings;
    Result<Scene> reference = client::load_scene(path, reference_warnings, options);
    options.stream_nodes = true;
    Result<Scene> fast = client::load_scene(path, warnings, options);
    EXPECT_EQ(fast.ok(), reference.ok()) << path;
    EXPECT_EQ(warnings, reference_warnings) << path;
    if (fast.ok() && reference.ok()) {
        expect_same_scene(*fast, *reference);
    } else if (!fast.ok() && !reference.ok()) {
        EXPECT_EQ(fast.error(), reference.error()) << path;
    }
    return fast;
}

inline Result<Scene> load_scene_both_ways(const std::filesystem::path& path) {
    std::vector<std::string> warnings;
    return load_scene_both_ways(path, warnings);
}

}  // namespace lc::test
