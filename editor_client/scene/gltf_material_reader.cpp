#include "editor_client/scene/gltf_material_reader.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "editor_client/scene/gltf_finite.h"
#include "editor_client/scene/gltf_texture_reader.h"
#include "editor_client/scene/texture_coordinates.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

namespace tg = tinygltf;

constexpr const char* kEmissiveStrengthExtension = "KHR_materials_emissive_strength";

// A number of an extension object (KHR_materials_*), when it is there.
bool extension_number(const tg::ExtensionMap& extensions, const char* extension, const char* key,
                      double& out) {
    auto found = extensions.find(extension);
    if (found == extensions.end() || !found->second.IsObject() || !found->second.Get(key).IsNumber()) {
        return false;
    }
    out = found->second.Get(key).GetNumberAsDouble();
    return true;
}

// A texture's use in the material, for choosing its texture coordinates.
struct TextureUse {
    const char* name;
    int index;
    int tex_coord;
    const tg::ExtensionMap* extensions;
};

class MaterialReader {
public:
    MaterialReader(const tg::Model& model, GltfDiagnostics& diagnostics, Scene& scene)
        : diagnostics_(diagnostics), textures_(model, diagnostics, scene.textures) {}

    Result<Material> read(const tg::Material& in, const std::string& what);

private:
    Status read_factors(const tg::Material& in, const std::string& what, Material& out) const;
    Status read_textures(const tg::Material& in, const std::string& what, Material& out);
    Status read_normal_texture(const tg::Material& in, const std::string& what, Material& out);
    Status read_texture_coordinates(const tg::Material& in, const std::string& what, Material& out);
    Result<TextureCoordinates> coordinates_of(const TextureUse& use, const std::string& what);
    Status read_alpha(const tg::Material& in, const std::string& what, Material& out);

    GltfDiagnostics& diagnostics_;
    GltfTextureReader textures_;
};

Result<Material> MaterialReader::read(const tg::Material& in, const std::string& what) {
    Material out;
    LC_RETURN_IF_ERROR(read_factors(in, what, out));
    LC_RETURN_IF_ERROR(read_textures(in, what, out));
    LC_RETURN_IF_ERROR(read_normal_texture(in, what, out));
    LC_RETURN_IF_ERROR(read_texture_coordinates(in, what, out));
    // Light passes through blended and transmissive surfaces (a lamp's
    // glass): they are drawn opaque but hide no light.
    double transmission = 0.0;
    extension_number(in.extensions, "KHR_materials_transmission", "transmissionFactor", transmission);
    out.casts_shadows = in.alphaMode != "BLEND" && !(transmission > 0.0);
    LC_RETURN_IF_ERROR(read_alpha(in, what, out));
    return out;
}

// Base colour, metallic, roughness and emission (times its strength).
Status MaterialReader::read_factors(const tg::Material& in, const std::string& what, Material& out) const {
    const std::vector<double>& base = in.pbrMetallicRoughness.baseColorFactor;
    if (base.size() != 4 || !all_finite(base)) {
        return diagnostics_.fail(what + ": baseColorFactor must be 4 finite numbers");
    }
    out.base_color_factor = glm::vec4(float(base[0]), float(base[1]), float(base[2]), float(base[3]));
    const double metallic = in.pbrMetallicRoughness.metallicFactor;
    const double roughness = in.pbrMetallicRoughness.roughnessFactor;
    if (!std::isfinite(metallic) || !std::isfinite(roughness)) {
        return diagnostics_.fail(what + ": metallicFactor and roughnessFactor must be finite");
    }
    out.metallic = float(std::clamp(metallic, 0.0, 1.0));
    out.roughness = float(std::clamp(roughness, 0.0, 1.0));
    if (in.emissiveFactor.size() != 3 || !all_finite(in.emissiveFactor)) {
        return diagnostics_.fail(what + ": emissiveFactor must be 3 finite numbers");
    }
    double strength = 1.0;
    if (extension_number(in.extensions, kEmissiveStrengthExtension, "emissiveStrength", strength) &&
        (!std::isfinite(strength) || strength < 0.0)) {
        return diagnostics_.fail(what + ": emissiveStrength must be finite and >= 0");
    }
    out.emissive_factor =
        glm::vec3(float(in.emissiveFactor[0] * strength), float(in.emissiveFactor[1] * strength),
                  float(in.emissiveFactor[2] * strength));
    for (int c = 0; c < 4; ++c) {
        if (out.base_color_factor[c] < 0.0f) return diagnostics_.fail(what + ": negative baseColorFactor");
    }
    for (int c = 0; c < 3; ++c) {
        if (out.emissive_factor[c] < 0.0f) return diagnostics_.fail(what + ": negative emissiveFactor");
    }
    return Ok{};
}

// Base colour and emissive (sRGB), metallic-roughness (linear).
Status MaterialReader::read_textures(const tg::Material& in, const std::string& what, Material& out) {
    Result<int> base =
        textures_.texture_for(in.pbrMetallicRoughness.baseColorTexture, what + " baseColorTexture");
    if (!base) return base.failure();
    out.base_color_texture = *base;
    Result<int> emissive = textures_.texture_for(in.emissiveTexture, what + " emissiveTexture");
    if (!emissive) return emissive.failure();
    out.emissive_texture = *emissive;
    Result<int> metallic_roughness = textures_.texture_for(
        in.pbrMetallicRoughness.metallicRoughnessTexture, what + " metallicRoughnessTexture", /*srgb=*/false);
    if (!metallic_roughness) return metallic_roughness.failure();
    out.metallic_roughness_texture = *metallic_roughness;
    return Ok{};
}

// normalTexture (linear data) and its scale.
Status MaterialReader::read_normal_texture(const tg::Material& in, const std::string& what, Material& out) {
    tg::TextureInfo info;
    info.index = in.normalTexture.index;
    info.texCoord = in.normalTexture.texCoord;
    Result<int> texture = textures_.texture_for(info, what + " normalTexture", /*srgb=*/false);
    if (!texture) return texture.failure();
    if (!std::isfinite(in.normalTexture.scale)) {
        return diagnostics_.fail(what + ": normalTexture.scale must be finite");
    }
    out.normal_texture = *texture;
    out.normal_scale = float(in.normalTexture.scale);
    return Ok{};
}

bool same_coordinates(const TextureCoordinates& a, const TextureCoordinates& b) {
    return a.set == b.set && a.transformed == b.transformed && a.offset == b.offset && a.scale == b.scale &&
           a.rotation == b.rotation;
}

// The coordinates of the material's first texture (base colour, normal,
// emissive, metallic-roughness); another texture asking for others is
// sampled with these, with a warning.
Status MaterialReader::read_texture_coordinates(const tg::Material& in, const std::string& what,
                                                Material& out) {
    const tg::PbrMetallicRoughness& pbr = in.pbrMetallicRoughness;
    const TextureUse uses[] = {
        {"baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
         &pbr.baseColorTexture.extensions},
        {"normalTexture", in.normalTexture.index, in.normalTexture.texCoord, &in.normalTexture.extensions},
        {"emissiveTexture", in.emissiveTexture.index, in.emissiveTexture.texCoord,
         &in.emissiveTexture.extensions},
        {"metallicRoughnessTexture", pbr.metallicRoughnessTexture.index,
         pbr.metallicRoughnessTexture.texCoord, &pbr.metallicRoughnessTexture.extensions}};
    bool chosen = false;
    for (const TextureUse& use : uses) {
        if (use.index < 0) continue;
        Result<TextureCoordinates> mine = coordinates_of(use, what + " " + use.name);
        if (!mine) return mine.failure();
        if (!chosen) {
            out.texture_coordinates = *mine;
            chosen = true;
        } else if (!same_coordinates(*mine, out.texture_coordinates)) {
            diagnostics_.warn(what + " " + use.name +
                              " asks for other texture coordinates than the material's "
                              "first texture; it is sampled with those");
        }
    }
    return Ok{};
}

// A KHR_texture_transform's numbers over `out`; only well-formed ones are taken.
void read_texture_transform(const tg::Value& t, TextureCoordinates& out) {
    out.transformed = true;
    auto pair = [&](const char* key, glm::vec2& into) {
        const tg::Value& v = t.Get(key);
        if (v.IsArray() && v.ArrayLen() == 2 && v.Get(0).IsNumber() && v.Get(1).IsNumber())
            into = glm::vec2(float(v.Get(0).GetNumberAsDouble()), float(v.Get(1).GetNumberAsDouble()));
    };
    pair("offset", out.offset);
    pair("scale", out.scale);
    if (t.Get("rotation").IsNumber()) out.rotation = float(t.Get("rotation").GetNumberAsDouble());
    if (t.Get("texCoord").IsInt()) out.set = t.Get("texCoord").GetNumberAsInt();
}

// One texture's set and KHR_texture_transform.
Result<TextureCoordinates> MaterialReader::coordinates_of(const TextureUse& use, const std::string& what) {
    TextureCoordinates out;
    out.set = use.tex_coord;
    auto ext = use.extensions->find("KHR_texture_transform");
    if (ext != use.extensions->end() && ext->second.IsObject()) {
        read_texture_transform(ext->second, out);
        if (!std::isfinite(out.offset.x) || !std::isfinite(out.offset.y) || !std::isfinite(out.scale.x) ||
            !std::isfinite(out.scale.y) || !std::isfinite(out.rotation))
            return diagnostics_.fail(what + ": KHR_texture_transform must hold finite numbers");
    }
    if (out.set < 0 || out.set > 1) {
        diagnostics_.warn(what + " uses TEXCOORD_" + std::to_string(out.set) +
                          "; only TEXCOORD_0 and TEXCOORD_1 are read, so it is sampled with TEXCOORD_0");
        out.set = 0;
    }
    return out;
}

// alphaMode, alphaCutoff and doubleSided; an unknown mode is drawn opaque.
Status MaterialReader::read_alpha(const tg::Material& in, const std::string& what, Material& out) {
    if (in.alphaMode == "MASK") {
        out.alpha_mode = AlphaMode::kMask;
    } else if (in.alphaMode == "BLEND") {
        out.alpha_mode = AlphaMode::kBlend;
    } else if (!in.alphaMode.empty() && in.alphaMode != "OPAQUE") {
        diagnostics_.warn(what + ": alphaMode '" + in.alphaMode +
                          "' is not OPAQUE, MASK or BLEND; drawn opaque");
    }
    if (!std::isfinite(in.alphaCutoff) || in.alphaCutoff < 0.0)
        return diagnostics_.fail(what + ": alphaCutoff must be finite and >= 0");
    out.alpha_cutoff = float(in.alphaCutoff);
    out.double_sided = in.doubleSided;
    return Ok{};
}

}  // namespace

Status read_gltf_materials(const tg::Model& model, GltfDiagnostics& diagnostics, Scene& scene) {
    MaterialReader reader(model, diagnostics, scene);
    for (size_t i = 0; i < model.materials.size(); ++i) {
        Result<Material> material = reader.read(model.materials[i], "material " + std::to_string(i));
        if (!material) return material.failure();
        scene.materials.push_back(*material);
    }
    return Ok{};
}

}  // namespace lc::client
