#include "editor_client/render/analysis/scene_effects.h"

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>

#include "lightcuts/material_model.h"
#include "editor_client/render/analysis/occlusion_analysis.h"
#include "editor_client/scene/surface_geometry.h"

namespace lc::client {
namespace {

struct LightCensus {
    size_t count[kLightTypeCount] = {};
    size_t with_range = 0;
    size_t classic = 0;

    void add(LightType type, float range) {
        ++count[static_cast<int>(type)];
        if (type != LightType::kDirectional && range > 0.0f) ++with_range;
    }
    size_t of(LightType type) const { return count[static_cast<int>(type)]; }
};

std::string plural(size_t n, const char* noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// Materials of drawn meshes with alphaMode MASK and BLEND.
struct AlphaCensus {
    size_t masked = 0;
    size_t blended = 0;
};

AlphaCensus count_alpha_materials(const Scene& scene) {
    std::vector<bool> drawn(scene.materials.size(), false);
    for (const Mesh& mesh : scene.meshes)
        if (!mesh.indices.empty() && mesh.material >= 0 && size_t(mesh.material) < drawn.size())
            drawn[size_t(mesh.material)] = true;
    AlphaCensus census;
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        if (!drawn[m]) continue;
        census.masked += scene.materials[m].alpha_mode == AlphaMode::kMask;
        census.blended += scene.materials[m].alpha_mode == AlphaMode::kBlend;
    }
    return census;
}

void decide_alpha(const Scene& scene, SceneEffects& effects) {
    const AlphaCensus census = count_alpha_materials(scene);
    const size_t masked_occluders = effects.occluder_masks.triangle_mask.empty()
                                        ? 0
                                        : size_t(std::count_if(effects.occluder_masks.triangle_mask.begin(),
                                                               effects.occluder_masks.triangle_mask.end(),
                                                               [](int32_t m) { return m >= 0; }));
    effects.decisions.push_back(
        {"alpha-masked cut-outs (alphaMode MASK)", census.masked > 0,
         census.masked > 0
             ? plural(census.masked, "drawn material") + " cut out where alpha < alphaCutoff; " +
                   plural(masked_occluders, "occluder triangle") + " let shadow rays through there"
             : "no drawn material has alphaMode MASK"});
    effects.decisions.push_back({"blended surfaces (alphaMode BLEND)", false,
                                 census.blended > 0
                                     ? plural(census.blended, "drawn material") +
                                           " with alphaMode BLEND: drawn opaque, casting no shadow"
                                     : "no drawn material has alphaMode BLEND"});
}

// Normal maps, texture coordinate sets and transforms, vertex colours: what
// the drawn meshes use (all of it is applied at load or in the G-buffer).
void decide_surface_inputs(const Scene& scene, SceneEffects& effects) {
    size_t normal_mapped = 0, second_set = 0, transformed = 0, coloured = 0;
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.indices.empty()) continue;
        coloured += !mesh.colors.empty();
        if (mesh.material < 0 || size_t(mesh.material) >= scene.materials.size()) continue;
        const Material& m = scene.materials[size_t(mesh.material)];
        normal_mapped += !mesh.tangents.empty();
        second_set += !mesh.uvs.empty() && m.texture_coordinates.set == 1;
        transformed += !mesh.uvs.empty() && m.texture_coordinates.transformed;
    }
    effects.decisions.push_back({"normal maps (normalTexture)", normal_mapped > 0,
                                 normal_mapped > 0 ? plural(normal_mapped, "drawn mesh") + " normal-mapped"
                                                   : "no drawn mesh has a normal map"});
    const bool sets = second_set + transformed > 0;
    effects.decisions.push_back({"texture coordinate sets and transforms (TEXCOORD_1, KHR_texture_transform)",
                                 sets,
                                 sets ? plural(second_set, "drawn mesh") + " sampled with TEXCOORD_1, " +
                                            plural(transformed, "drawn mesh") + " with KHR_texture_transform"
                                      : "every drawn texture is sampled with TEXCOORD_0 as it is"});
    effects.decisions.push_back(
        {"vertex colours (COLOR_0)", coloured > 0,
         coloured > 0 ? plural(coloured, "drawn mesh") + " with COLOR_0" : "no drawn mesh has COLOR_0"});
}

// Records one decision; returns whether the effect is simulated.
bool decide(SceneEffects& effects, const std::string& name, bool on, const std::string& why_on,
            const std::string& why_off) {
    effects.decisions.push_back({name, on, on ? why_on : why_off});
    return on;
}

// The lights that are shaded, by type, and where they are: cluster
// representatives are leaves, so the leaves (or the scene lights) and the
// classic lights are every light shaded and every position.
struct ShadedLights {
    LightCensus census;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> directions;

    void add(LightType type, float range, const glm::vec3& position, const glm::vec3& direction) {
        census.add(type, range);
        if (type == LightType::kDirectional) {
            directions.push_back(direction);
        } else {
            positions.push_back(position);
        }
    }
};

ShadedLights shaded_lights(const Scene& scene, const WalkTree* tree) {
    ShadedLights lights;
    if (tree != nullptr) {
        for (const GpuLight& leaf : tree->leaves)
            lights.add(LightType(leaf.type), leaf.range, leaf.position, leaf.direction);
    }
    for (const SceneLight& light : scene.lights) {
        if (!light.classic && tree != nullptr) continue;
        lights.census.classic += light.classic;
        lights.add(light.type, light.range, light.position, light.direction);
    }
    return lights;
}

// What the drawn materials sample and reflect.
struct MaterialCensus {
    bool textured = false;
    // Which kinds of texture the drawn materials sample, for the report.
    bool base_colour_texture = false, emissive_texture = false, metallic_roughness_texture = false,
         normal_texture = false;
    bool emissive = false;
    bool glossy_texture = false;
    size_t glossy_materials = 0;
};

MaterialCensus census_materials(const Scene& scene) {
    MaterialCensus census;
    std::vector<bool> glossy(scene.materials.size(), false);  // per drawn material
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.indices.empty()) continue;
        if (mesh.material < 0 || size_t(mesh.material) >= scene.materials.size()) continue;
        const Material& m = scene.materials[mesh.material];
        auto valid_texture = [&](int index) {
            return index >= 0 && size_t(index) < scene.textures.size() && !mesh.uvs.empty();
        };
        census.base_colour_texture |= valid_texture(m.base_color_texture);
        bool emits = glm::any(glm::greaterThan(m.emissive_factor, glm::vec3(0.0f)));
        if (emits) census.emissive = true;
        census.emissive_texture |= emits && valid_texture(m.emissive_texture);
        // A normal map is sampled where the mesh has tangents (read or generated).
        census.normal_texture |= valid_texture(m.normal_texture) && !mesh.tangents.empty();
        // A lobe exists where roughness < 1 (n > 0) and F0 > 0; a texture can
        // lower the roughness anywhere.
        const bool textured_lobe = valid_texture(m.metallic_roughness_texture);
        census.metallic_roughness_texture |= textured_lobe;
        census.glossy_texture |= textured_lobe;
        const shading::SurfaceMaterial lobe = shading::surface_material(
            glm::dvec3(m.base_color_factor), m.metallic, m.roughness);
        if (textured_lobe || shading::has_lobe(lobe.specular, lobe.exponent))
            glossy[size_t(mesh.material)] = true;
    }
    census.glossy_materials = size_t(std::count(glossy.begin(), glossy.end(), true));
    census.textured = census.base_colour_texture || census.emissive_texture ||
                      census.metallic_roughness_texture || census.normal_texture;
    return census;
}

void decide_light_types(const LightCensus& census, const std::string& has, SceneEffects& effects) {
    const size_t points = census.of(LightType::kPoint), spots = census.of(LightType::kSpot),
                 directionals = census.of(LightType::kDirectional),
                 orienteds = census.of(LightType::kOriented);
    effects.point_lights = decide(effects, "point lights (inverse-square falloff)", points > 0,
                                  has + plural(points, "point light"), has + "no point lights");
    effects.spot_lights = decide(effects, "spot cone attenuation", spots > 0,
                                 has + plural(spots, "spot light"), has + "no spot lights");
    effects.directional_lights =
        decide(effects, "directional lights", directionals > 0,
               has + plural(directionals, "directional light"), has + "no directional lights");
    effects.oriented_lights =
        decide(effects, "oriented lights (cosine emitters)", orienteds > 0,
               has + plural(orienteds, "oriented light"), has + "no oriented lights");
    effects.range_window = decide(effects, "range windowing (KHR_lights_punctual)", census.with_range > 0,
                                  plural(census.with_range, "light") + " with a range",
                                  "no point or spot light has a range");
    effects.classic_lights =
        decide(effects, "classic lights (shaded one by one)", census.classic > 0,
               plural(census.classic, "light") + " marked classic", "no light is marked classic");
}

// "base colour and normal": the kinds of texture the drawn materials sample.
std::string texture_kinds(const MaterialCensus& materials) {
    std::vector<std::string> kinds;
    if (materials.base_colour_texture) kinds.push_back("base colour");
    if (materials.emissive_texture) kinds.push_back("emissive");
    if (materials.metallic_roughness_texture) kinds.push_back("metallic-roughness");
    if (materials.normal_texture) kinds.push_back("normal");
    std::string text;
    for (size_t i = 0; i < kinds.size(); ++i)
        text += (i == 0 ? "" : i + 1 == kinds.size() ? " and " : ", ") + kinds[i];
    return text;
}

void decide_material_inputs(const MaterialCensus& materials, SceneEffects& effects) {
    effects.textures = decide(effects, "base colour, emissive, metallic-roughness and normal textures",
                              materials.textured, "drawn materials sample " + texture_kinds(materials) + " textures",
                              "no drawn material has a texture (with texture coordinates)");
    effects.emissive = decide(effects, "emissive surfaces", materials.emissive,
                              "a drawn material has a non-zero emissive factor",
                              "no drawn material emits light");
}

// Bounced light is the server's (bake --indirect): the renderer traces no
// bounce of its own, it clamps or leaves out the tree's indirect lights.
void count_indirect_lights(const WalkTree* tree, SceneEffects& effects) {
    if (tree == nullptr) return;
    for (const GpuLight& leaf : tree->leaves) {
        effects.indirect_lights += is_indirect(leaf);
        effects.indirect_patches += is_patch(leaf);
    }
}

// Area lights light the scene through the tree's oriented leaves, which the
// server sampled from the emissive triangles (area_light_sampler.h).
void decide_area_lights(const Scene& scene, const WalkTree* tree, size_t orienteds, SceneEffects& effects) {
    const size_t emissive_triangles = emissive_triangle_count(extract_surface_geometry(scene));
    // The indirect lights are oriented too, but no area light's samples.
    const size_t samples = tree != nullptr ? orienteds - size_t(effects.indirect_lights) : 0;
    if (emissive_triangles == 0) {
        decide(effects, "area lights", false, "", "no drawn triangle emits power");
        return;
    }
    decide(effects, "area lights", samples > 0,
           plural(emissive_triangles, "emissive triangle") + ", " + plural(samples, "sample"),
           plural(emissive_triangles, "emissive triangle") +
               " but the tree holds no area-light samples (bake with the scene's geometry)");
}

void decide_shadows(const Scene& scene, const ShadedLights& lights, ShadowMode shadow_mode,
                    SceneEffects& effects) {
    const std::string shadows = "shadows (a shadow ray per evaluated light or cluster)";
    if (shadow_mode == ShadowMode::kOff) {
        decide(effects, shadows, false, "", "--shadows off: every light is treated as visible (V = 1)");
        return;
    }
    const bool forced = shadow_mode == ShadowMode::kOn;
    OcclusionAnalysis occlusion = analyse_occlusion(scene, lights.positions, lights.directions, !forced);
    const std::string why = (forced ? "--shadows on: " : "") + occlusion.reason;
    effects.shadows = decide(effects, shadows, occlusion.possible, why, why + "; V = 1");
    effects.occluders = std::move(occlusion.occluders);
    effects.occluder_masks = std::move(occlusion.masks);
}

void decide_specular(const MaterialCensus& materials, SceneEffects& effects) {
    effects.specular = decide(
        effects, "glossy reflection (a lobe around the mirror direction, material_model.h)",
        materials.glossy_materials > 0,
        plural(materials.glossy_materials, "drawn material") + " with roughness below 1" +
            (materials.glossy_texture ? " or a metallic-roughness texture" : ""),
        "every drawn material has roughness 1, where the lobe is constant and shades as Lambert");
}

void decide_indirect(bool indirect, SceneEffects& effects) {
    const std::string name = "indirect light (the paper's automatic clamping)";
    const std::string baked = plural(effects.indirect_lights, "indirect light") +
                              " of the tree (bake --indirect; among the oriented lights above)";
    if (effects.indirect_lights == 0) {
        decide(effects, name, false, "",
               "the tree holds no indirect light: bounced light is baked on the server "
               "(bake --indirect vpl|radiosity)");
    } else if (!indirect) {
        effects.indirect_off = true;
        decide(effects, name, false, "", "--indirect off: " + baked + " left out");
    } else {
        const uint64_t vpls = effects.indirect_lights - effects.indirect_patches;
        effects.indirect_clamp = decide(effects, name, true,
                                        baked + ": " + plural(vpls, "VPL") +
                                            " clamped to half the error ratio of the pixel's total each, " +
                                            plural(effects.indirect_patches, "radiosity patch light") +
                                            " shaded as disks of their area",
                                        "");
    }
}

}  // namespace

std::vector<EffectDecision> SceneEffects::simulated() const {
    std::vector<EffectDecision> out;
    std::copy_if(decisions.begin(), decisions.end(), std::back_inserter(out),
                 [](const EffectDecision& d) { return d.simulated; });
    return out;
}

std::vector<EffectDecision> SceneEffects::skipped() const {
    std::vector<EffectDecision> out;
    std::copy_if(decisions.begin(), decisions.end(), std::back_inserter(out),
                 [](const EffectDecision& d) { return !d.simulated; });
    return out;
}

SceneEffects analyse_scene_effects(const Scene& scene, const WalkTree* tree, ShadowMode shadow_mode,
                                   bool indirect) {
    const ShadedLights lights = shaded_lights(scene, tree);
    const MaterialCensus materials = census_materials(scene);
    const std::string has =
        tree != nullptr ? "the tree and the classic lights have " : "the scene has ";
    SceneEffects effects;
    decide_light_types(lights.census, has, effects);
    decide_material_inputs(materials, effects);
    count_indirect_lights(tree, effects);
    decide_area_lights(scene, tree, lights.census.of(LightType::kOriented), effects);
    decide_shadows(scene, lights, shadow_mode, effects);
    decide_alpha(scene, effects);
    decide_surface_inputs(scene, effects);
    decide_specular(materials, effects);
    decide_indirect(indirect, effects);
    return effects;
}

nlohmann::json effects_json(const std::vector<EffectDecision>& decisions) {
    nlohmann::json out = nlohmann::json::array();
    for (const EffectDecision& d : decisions)
        out.push_back({{"name", d.name}, {"reason", d.reason}});
    return out;
}

}  // namespace lc::client
