// The CPU/GPU interface (lightcuts/device/), checked on the compiled shaders:
// every embedded SPIR-V module is reflected with spirv-cross, and each storage
// buffer's element struct (member names, offsets, array stride), push
// constant, descriptor binding and specialization-constant id must be what
// the C++ side has. Needs no GPU.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/device/restir.h"
#include "lightcuts/device/spec_constants.h"
#include "shader_modules.h"

namespace lc {
namespace {

using nlohmann::json;

struct Field {
    std::string name;
    size_t offset;
};

struct CppStruct {
    size_t size;
    std::vector<Field> fields;  // in declaration order
};

#define LC_FIELD(type, member) Field{#member, offsetof(type, member)}

// The C++ side of every struct a shader declares, by its GLSL name.
const std::map<std::string, CppStruct>& cpp_structs() {
    static const std::map<std::string, CppStruct> structs = {
        {"GpuLight",
         {sizeof(GpuLight),
          {LC_FIELD(GpuLight, position), LC_FIELD(GpuLight, range), LC_FIELD(GpuLight, direction),
           LC_FIELD(GpuLight, type), LC_FIELD(GpuLight, intensity), LC_FIELD(GpuLight, spot_cos_outer),
           LC_FIELD(GpuLight, spot_cos_inner), LC_FIELD(GpuLight, spot_scale), LC_FIELD(GpuLight, flags),
           LC_FIELD(GpuLight, source_radius)}}},
        {"GpuTreeNode",
         {sizeof(GpuTreeNode),
          {LC_FIELD(GpuTreeNode, intensity), LC_FIELD(GpuTreeNode, representative),
           LC_FIELD(GpuTreeNode, bbox_min), LC_FIELD(GpuTreeNode, first_child),
           LC_FIELD(GpuTreeNode, bbox_max), LC_FIELD(GpuTreeNode, escape), LC_FIELD(GpuTreeNode, radius),
           LC_FIELD(GpuTreeNode, cone_axis), LC_FIELD(GpuTreeNode, cone_cos), LC_FIELD(GpuTreeNode, flags)}}},
        {"GpuFrameCounters",
         {sizeof(GpuFrameCounters),
          {LC_FIELD(GpuFrameCounters, max_cut), LC_FIELD(GpuFrameCounters, nonfinite_pixels),
           LC_FIELD(GpuFrameCounters, geometry_pixels), LC_FIELD(GpuFrameCounters, max_cut_hits),
           LC_FIELD(GpuFrameCounters, loop_limit_stops), LC_FIELD(GpuFrameCounters, shadow_rays),
           LC_FIELD(GpuFrameCounters, shadow_rays_high),
           LC_FIELD(GpuFrameCounters, reconstruction_fallbacks)}}},
        {"GpuWalkState",
         {sizeof(GpuWalkState),
          {LC_FIELD(GpuWalkState, radiance),
           LC_FIELD(GpuWalkState, size),
           LC_FIELD(GpuWalkState, hash),
           LC_FIELD(GpuWalkState, tau),
           LC_FIELD(GpuWalkState, fit_hi),
           LC_FIELD(GpuWalkState, over_lo),
           LC_FIELD(GpuWalkState, flags),
           LC_FIELD(GpuWalkState, passes),
           LC_FIELD(GpuWalkState, pad1),
           LC_FIELD(GpuWalkState, pad2),
           LC_FIELD(GpuWalkState, indirect_largest),
           LC_FIELD(GpuWalkState, indirect_leaves),
           LC_FIELD(GpuWalkState, indirect_second),
           LC_FIELD(GpuWalkState, indirect_energy),
           LC_FIELD(GpuWalkState, indirect_rest),
           LC_FIELD(GpuWalkState, clamped_energy),
           LC_FIELD(GpuWalkState, indirect_clusters),
           LC_FIELD(GpuWalkState, indirect_rest_max),
           LC_FIELD(GpuWalkState, indirect_others),
           LC_FIELD(GpuWalkState, pad3),
           LC_FIELD(GpuWalkState, clamp_threshold),
           LC_FIELD(GpuWalkState, clamp_change),
           LC_FIELD(GpuWalkState, clamp_below),
           LC_FIELD(GpuWalkState, pad4),
           LC_FIELD(GpuWalkState, clamp_above),
           LC_FIELD(GpuWalkState, pad5)}}},
        {"GpuFrameConstants",
         {sizeof(GpuFrameConstants),
          {LC_FIELD(GpuFrameConstants, width), LC_FIELD(GpuFrameConstants, height),
           LC_FIELD(GpuFrameConstants, leaf_count), LC_FIELD(GpuFrameConstants, classic_count),
           LC_FIELD(GpuFrameConstants, node_count), LC_FIELD(GpuFrameConstants, exposure),
           LC_FIELD(GpuFrameConstants, scale_bar_rows), LC_FIELD(GpuFrameConstants, shadow_bias),
           LC_FIELD(GpuFrameConstants, light_begin), LC_FIELD(GpuFrameConstants, light_end),
           LC_FIELD(GpuFrameConstants, bvh_node_count), LC_FIELD(GpuFrameConstants, walk_dispatch),
           LC_FIELD(GpuFrameConstants, eye), LC_FIELD(GpuFrameConstants, clamp_pass),
           LC_FIELD(GpuFrameConstants, clamp_passes), LC_FIELD(GpuFrameConstants, lattice_step),
           LC_FIELD(GpuFrameConstants, lattice_origin_x), LC_FIELD(GpuFrameConstants, lattice_origin_y),
           LC_FIELD(GpuFrameConstants, frame_seed), LC_FIELD(GpuFrameConstants, vpl_visibility_stride),
           LC_FIELD(GpuFrameConstants, frame_number), LC_FIELD(GpuFrameConstants, draw_seed)}}},
        {"GpuReconstructionSample",
         {sizeof(GpuReconstructionSample),
          {LC_FIELD(GpuReconstructionSample, radiance), LC_FIELD(GpuReconstructionSample, record_count),
           LC_FIELD(GpuReconstructionSample, flags), LC_FIELD(GpuReconstructionSample, reached_ratio),
           LC_FIELD(GpuReconstructionSample, pad1), LC_FIELD(GpuReconstructionSample, pad2)}}},
        {"GpuCutRecords", {sizeof(GpuCutRecords), {LC_FIELD(GpuCutRecords, words)}}},
        {"GpuDrawPair",
         {sizeof(GpuDrawPair),
          {LC_FIELD(GpuDrawPair, centre0), LC_FIELD(GpuDrawPair, radius0), LC_FIELD(GpuDrawPair, centre1),
           LC_FIELD(GpuDrawPair, radius1), LC_FIELD(GpuDrawPair, intensity0), LC_FIELD(GpuDrawPair, intensity1),
           LC_FIELD(GpuDrawPair, child0), LC_FIELD(GpuDrawPair, child1)}}},
        {"GpuReservoir",
         {sizeof(GpuReservoir),
          {LC_FIELD(GpuReservoir, position), LC_FIELD(GpuReservoir, light), LC_FIELD(GpuReservoir, normal),
           LC_FIELD(GpuReservoir, weight), LC_FIELD(GpuReservoir, count), LC_FIELD(GpuReservoir, target),
           LC_FIELD(GpuReservoir, pad0), LC_FIELD(GpuReservoir, pad1)}}},
        {"GpuPrimaryTriangle",
         {sizeof(GpuPrimaryTriangle),
          {LC_FIELD(GpuPrimaryTriangle, v0), LC_FIELD(GpuPrimaryTriangle, v1), LC_FIELD(GpuPrimaryTriangle, v2),
           LC_FIELD(GpuPrimaryTriangle, draw)}}},
        {"GpuSurfaceMaterial",
         {sizeof(GpuSurfaceMaterial),
          {LC_FIELD(GpuSurfaceMaterial, base_color_factor), LC_FIELD(GpuSurfaceMaterial, emissive_metallic),
           LC_FIELD(GpuSurfaceMaterial, roughness), LC_FIELD(GpuSurfaceMaterial, flags),
           LC_FIELD(GpuSurfaceMaterial, pad0), LC_FIELD(GpuSurfaceMaterial, pad1)}}},
        {"GpuSceneVertex",
         {sizeof(GpuSceneVertex),
          {LC_FIELD(GpuSceneVertex, position_normal_x), LC_FIELD(GpuSceneVertex, normal_yz_uv),
           LC_FIELD(GpuSceneVertex, tangent), LC_FIELD(GpuSceneVertex, color)}}},
        {"GpuPrimaryParams",
         {sizeof(GpuPrimaryParams),
          {LC_FIELD(GpuPrimaryParams, inverse_view_proj), LC_FIELD(GpuPrimaryParams, eye),
           LC_FIELD(GpuPrimaryParams, node_count)}}},
        {"GpuTemporalParams",
         {sizeof(GpuTemporalParams),
          {LC_FIELD(GpuTemporalParams, previous_view_proj), LC_FIELD(GpuTemporalParams, history_valid),
           LC_FIELD(GpuTemporalParams, camera_moved), LC_FIELD(GpuTemporalParams, still_history_cap),
           LC_FIELD(GpuTemporalParams, moving_history_cap), LC_FIELD(GpuTemporalParams, filter_frames),
           LC_FIELD(GpuTemporalParams, position_tolerance), LC_FIELD(GpuTemporalParams, pad0),
           LC_FIELD(GpuTemporalParams, pad1)}}},
        {"GpuDrawConstants",
         {sizeof(GpuDrawConstants),
          {LC_FIELD(GpuDrawConstants, view_proj), LC_FIELD(GpuDrawConstants, base_color_factor),
           LC_FIELD(GpuDrawConstants, emissive_metallic), LC_FIELD(GpuDrawConstants, eye_roughness),
           LC_FIELD(GpuDrawConstants, flags), LC_FIELD(GpuDrawConstants, alpha_cutoff),
           LC_FIELD(GpuDrawConstants, normal_scale), LC_FIELD(GpuDrawConstants, pad2)}}},
        {"GpuBackground",
         {sizeof(GpuBackground),
          {LC_FIELD(GpuBackground, ray_at_origin), LC_FIELD(GpuBackground, kind),
           LC_FIELD(GpuBackground, ray_step_x), LC_FIELD(GpuBackground, intensity),
           LC_FIELD(GpuBackground, ray_step_y), LC_FIELD(GpuBackground, rotation),
           LC_FIELD(GpuBackground, sun_direction), LC_FIELD(GpuBackground, turbidity),
           LC_FIELD(GpuBackground, sun_radiance), LC_FIELD(GpuBackground, sun_cos_radius),
           LC_FIELD(GpuBackground, map_width), LC_FIELD(GpuBackground, map_height),
           LC_FIELD(GpuBackground, pad0), LC_FIELD(GpuBackground, pad1)}}},
        {"GpuEnvironmentTexel",
         {sizeof(GpuEnvironmentTexel),
          {LC_FIELD(GpuEnvironmentTexel, radiance), LC_FIELD(GpuEnvironmentTexel, pad0)}}},
        {"GpuBvhNode",
         {sizeof(GpuBvhNode),
          {LC_FIELD(GpuBvhNode, bbox_min), LC_FIELD(GpuBvhNode, escape), LC_FIELD(GpuBvhNode, bbox_max),
           LC_FIELD(GpuBvhNode, triangles)}}},
        {"GpuWideBvhNode",
         {sizeof(GpuWideBvhNode),
          {LC_FIELD(GpuWideBvhNode, lo_x), LC_FIELD(GpuWideBvhNode, hi_x), LC_FIELD(GpuWideBvhNode, lo_y),
           LC_FIELD(GpuWideBvhNode, hi_y), LC_FIELD(GpuWideBvhNode, lo_z), LC_FIELD(GpuWideBvhNode, hi_z),
           LC_FIELD(GpuWideBvhNode, children), LC_FIELD(GpuWideBvhNode, order)}}},
        {"GpuShadowTriangle",
         {sizeof(GpuShadowTriangle),
          {LC_FIELD(GpuShadowTriangle, v0), LC_FIELD(GpuShadowTriangle, masked),
           LC_FIELD(GpuShadowTriangle, edge1), LC_FIELD(GpuShadowTriangle, pad1),
           LC_FIELD(GpuShadowTriangle, edge2), LC_FIELD(GpuShadowTriangle, pad2)}}},
        {"GpuMaskedTriangle",
         {sizeof(GpuMaskedTriangle),
          {LC_FIELD(GpuMaskedTriangle, uv0), LC_FIELD(GpuMaskedTriangle, uv1),
           LC_FIELD(GpuMaskedTriangle, uv2), LC_FIELD(GpuMaskedTriangle, mask),
           LC_FIELD(GpuMaskedTriangle, pad0)}}},
        {"GpuMaskTexels", {sizeof(GpuMaskTexels), {LC_FIELD(GpuMaskTexels, words)}}},
        {"GpuVisibilityBits", {sizeof(GpuVisibilityBits), {LC_FIELD(GpuVisibilityBits, words)}}},
        {"GpuAlphaMask",
         {sizeof(GpuAlphaMask),
          {LC_FIELD(GpuAlphaMask, texel_offset), LC_FIELD(GpuAlphaMask, width),
           LC_FIELD(GpuAlphaMask, height), LC_FIELD(GpuAlphaMask, keep_threshold)}}},
    };
    return structs;
}

// A storage buffer or push-constant block: one member, a struct or a runtime
// array of structs.
struct Block {
    int64_t binding;  // -1: push constants
    std::string element;
    int64_t set = 0;  // the frame's set, or the real-time mode's (kTemporalSet)
    // The pipeline layout beside the frame's set 0 ("": the frame's alone,
    // "primary": PrimaryRaysPass's, whose set 1 is not the temporal set).
    std::string layout;
};

// Every block, image and specialization constant a shader may declare.
const std::map<std::string, Block>& known_blocks() {
    static const std::map<std::string, Block> blocks = {
        {"LeafLights", {kBindLeafLights, "GpuLight"}},
        {"TreeNodes", {kBindTreeNodes, "GpuTreeNode"}},
        {"ClassicLights", {kBindClassicLights, "GpuLight"}},
        {"FrameCounters", {kBindCounters, "GpuFrameCounters"}},
        {"BvhNodes", {kBindBvhNodes, "GpuWideBvhNode"}},
        {"ShadowTriangles", {kBindShadowTriangles, "GpuShadowTriangle"}},
        {"MaskedTriangles", {kBindMaskedTriangles, "GpuMaskedTriangle"}},
        {"AlphaMasks", {kBindAlphaMasks, "GpuAlphaMask"}},
        {"MaskTexels", {kBindMaskTexels, "GpuMaskTexels"}},
        {"VplVisibility", {kBindVplVisibility, "GpuVisibilityBits"}},
        {"WalkStates", {kBindWalkStates, "GpuWalkState"}},
        {"Background", {kBindBackground, "GpuBackground"}},
        {"EnvironmentTexels", {kBindEnvironmentTexels, "GpuEnvironmentTexel"}},
        {"FrameConstants", {-1, "GpuFrameConstants"}},
        {"DrawConstants", {-1, "GpuDrawConstants"}},
        {"TemporalParams", {kBindTemporalParams, "GpuTemporalParams", kTemporalSet}},
        {"DrawPairs", {kBindDrawPairs, "GpuDrawPair", kDrawPairSet}},
        {"ReservoirsPrevious", {kBindReservoirsPrevious, "GpuReservoir", kRestirSet}},
        {"ReservoirsTemporal", {kBindReservoirsTemporal, "GpuReservoir", kRestirSet}},
        {"ReservoirsFinal", {kBindReservoirsFinal, "GpuReservoir", kRestirSet}},
        {"PrimaryNodes", {kBindPrimaryNodes, "GpuBvhNode", kPrimarySet, "primary"}},
        {"PrimaryTriangles", {kBindPrimaryTriangles, "GpuShadowTriangle", kPrimarySet, "primary"}},
        {"PrimarySources", {kBindPrimarySources, "GpuPrimaryTriangle", kPrimarySet, "primary"}},
        {"SceneVertices", {kBindSceneVertices, "GpuSceneVertex", kPrimarySet, "primary"}},
        {"SurfaceMaterials", {kBindSurfaceMaterials, "GpuSurfaceMaterial", kPrimarySet, "primary"}},
        {"PrimaryParams", {kBindPrimaryParams, "GpuPrimaryParams", kPrimarySet, "primary"}},
        {"ReconstructionSamples",
         {kBindReconstructionSamples, "GpuReconstructionSample", kReconstructionSet, "reconstruction"}},
        {"CutRecords", {kBindReconstructionRecords, "GpuCutRecords", kReconstructionSet, "reconstruction"}},
    };
    return blocks;
}

const std::map<std::string, uint32_t>& known_images() {
    static const std::map<std::string, uint32_t> images = {
        {"gbuffer_position", kBindPosition},
        {"gbuffer_normal", kBindNormal},
        {"gbuffer_albedo", kBindAlbedo},
        {"gbuffer_emissive", kBindEmissive},
        {"hdr_image", kBindHdr},
        {"cut_image", kBindCut},
        {"display_image", kBindDisplay},
        {"base_color_texture", kBindBaseColorTexture},
        {"emissive_texture", kBindEmissiveTexture},
        {"metallic_roughness_texture", kBindMetallicRoughnessTexture},
        {"normal_texture", kBindNormalTexture},
    };
    return images;
}

// The real-time mode's own set (kTemporalSet, shaders/temporal_bindings.glsl).
const std::map<std::string, uint32_t>& known_temporal_images() {
    static const std::map<std::string, uint32_t> images = {
        {"history_in", kBindHistoryIn},
        {"history_out", kBindHistoryOut},
        {"history_position_in", kBindHistoryPositionIn},
        {"history_position_out", kBindHistoryPositionOut},
    };
    return images;
}

const std::map<std::string, uint32_t>& known_spec_constants() {
    static const std::map<std::string, uint32_t> ids = {
        {"kPointLights", kSpecPointLights},
        {"kSpotLights", kSpecSpotLights},
        {"kDirectionalLights", kSpecDirectionalLights},
        {"kOrientedLights", kSpecOrientedLights},
        {"kRangeWindow", kSpecRangeWindow},
        {"kClassicLights", kSpecClassicLights},
        {"kEmissive", kSpecEmissive},
        {"kShadows", kSpecShadows},
        {"kAlphaMasks", kSpecAlphaMasks},
        {"kSpecular", kSpecSpecular},
        {"kView", kSpecCutView},
        {"kTextures", kSpecTextures},
        {"kErrorRatio", kSpecErrorRatio},
        {"kMaxCut", kSpecMaxCut},
        {"kHeapCapacity", kSpecHeapCapacity},
        {"kWalkMaxCut", kSpecWalkMaxCut},
        {"kWalkMaxPasses", kSpecWalkMaxPasses},
        {"kWalkShrink", kSpecWalkShrink},
        {"kWalkMargin", kSpecWalkMargin},
        {"kWalkBisections", kSpecWalkBisections},
        {"kIndirectClamp", kSpecIndirectClamp},
        {"kIndirectOff", kSpecIndirectOff},
        {"kWalkShareCuts", kSpecWalkShareCuts},
        {"kRepresentatives", kSpecRepresentatives},
        {"kRepresentativeSeed", kSpecRepresentativeSeed},
        {"kStochasticCut", kSpecStochasticCut},
        {"kStochasticRays", kSpecStochasticRays},
        {"kCandidates", kSpecRestirCandidates},
        {"kSource", kSpecRestirSource},
        {"kSpatial", kSpecRestirSpatial},
        {"kTemporal", kSpecRestirTemporal},
        {"kUnbiased", kSpecRestirUnbiased},
        {"kCandidateVisibility", kSpecRestirCandidateVisibility},
        {"kBlock", kSpecReconstructionBlock},
        {"kRecordCap", kSpecReconstructionCap},
    };
    return ids;
}

// render_throughput_bench's baseline kernel keeps a set and constants of its
// own (binding 0: lights, 1: result); only its GpuLight array is shared.
constexpr const char* kBenchmarkModule = "light_loop_minimal.comp";

// spirv-cross --reflect of one module.
json reflect(const LcShaderModule& module) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("lc_shader_interface_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::filesystem::path spv = dir / (std::string(module.name) + ".spv");
    const std::filesystem::path out = dir / (std::string(module.name) + ".json");
    {
        std::ofstream file(spv, std::ios::binary);
        file.write(reinterpret_cast<const char*>(module.words.data()),
                   std::streamsize(module.words.size_bytes()));
    }
    // The module first: --reflect takes an optional argument.
    const std::string command =
        "spirv-cross '" + spv.string() + "' --reflect --output '" + out.string() + "' 2>&1";
    const int status = std::system(command.c_str());
    json reflection;
    if (status == 0) {
        std::ifstream file(out);
        reflection = json::parse(file, nullptr, /*allow_exceptions=*/false);
    }
    std::filesystem::remove_all(dir);
    if (status != 0)
        ADD_FAILURE() << "spirv-cross failed on " << module.name
                      << " (installed by scripts/install_deps.sh?)";
    return reflection;
}

bool is_struct_type(const json& types, const json& type) {
    return type.is_string() && types.contains(type.get<std::string>());
}

// std430 size of a member of a non-struct type (the shared structs use no others).
size_t scalar_or_vector_size(const std::string& type) {
    static const std::map<std::string, size_t> sizes = {{"float", 4},  {"uint", 4},  {"int", 4},
                                                        {"vec2", 8},   {"vec3", 12}, {"vec4", 16},
                                                        {"uvec4", 16}, {"mat4", 64}};
    auto it = sizes.find(type);
    return it == sizes.end() ? 0 : it->second;
}

// Checks the struct `type_id` member by member against the C++ struct of the
// same name (recursing into nested structs); returns its std430 extent.
size_t expect_struct_matches(const json& types, const std::string& type_id,
                             const std::string& where) {
    const json& type = types.at(type_id);
    const std::string name = type.at("name").get<std::string>();
    auto it = cpp_structs().find(name);
    if (it == cpp_structs().end()) {
        ADD_FAILURE() << where << ": struct " << name << " is not in lightcuts/device/gpu_structs.h";
        return 0;
    }
    const CppStruct& cpp = it->second;
    const json& members = type.at("members");
    EXPECT_EQ(members.size(), cpp.fields.size()) << where << ": members of " << name;
    size_t extent = 0;
    for (size_t m = 0; m < members.size() && m < cpp.fields.size(); ++m) {
        const json& member = members[m];
        const std::string label = where + ": " + name + "." + cpp.fields[m].name;
        EXPECT_EQ(member.at("name").get<std::string>(), cpp.fields[m].name) << label;
        const size_t offset = member.at("offset").get<size_t>();
        EXPECT_EQ(offset, cpp.fields[m].offset) << label;
        const size_t size = is_struct_type(types, member.at("type"))
                                ? expect_struct_matches(types, member.at("type"), label)
                                : scalar_or_vector_size(member.at("type").get<std::string>());
        EXPECT_GT(size, 0u) << label << ": unexpected type " << member.at("type");
        extent = std::max(extent, offset + size);
    }
    // Every shared struct holds a 16-byte-aligned member: std430 rounds to 16.
    EXPECT_EQ((extent + 15) / 16 * 16, cpp.size) << where << ": size of " << name;
    return cpp.size;
}

// A block: one member, a struct (offset 0) or a runtime array of structs
// whose stride is the C++ size.
void expect_block_matches(const json& types, const json& resource, const Block& block,
                          const std::string& where) {
    const json& type = types.at(resource.at("type").get<std::string>());
    const json& members = type.at("members");
    ASSERT_EQ(members.size(), 1u) << where << ": one member per block";
    const json& member = members[0];
    ASSERT_TRUE(is_struct_type(types, member.at("type"))) << where;
    const std::string element = types.at(member.at("type").get<std::string>()).at("name");
    EXPECT_EQ(element, block.element) << where;
    EXPECT_EQ(member.at("offset").get<size_t>(), 0u) << where;
    expect_struct_matches(types, member.at("type"), where);
    if (member.contains("array")) {
        auto it = cpp_structs().find(block.element);
        ASSERT_NE(it, cpp_structs().end()) << where;
        EXPECT_EQ(member.at("array_stride").get<size_t>(), it->second.size)
            << where << ": array stride of " << block.element;
    }
}

struct Seen {
    std::set<std::string> blocks, images, spec_constants;
};

void expect_module_matches(const LcShaderModule& module, Seen& seen) {
    const json reflection = reflect(module);
    ASSERT_TRUE(reflection.is_object()) << module.name << ": no reflection";
    const bool benchmark = std::string(module.name) == kBenchmarkModule;
    const json& types = reflection.contains("types") ? reflection.at("types") : json::object();
    for (const char* kind : {"ssbos", "push_constants"}) {
        if (!reflection.contains(kind)) continue;
        for (const json& resource : reflection.at(kind)) {
            const std::string block_name = types.at(resource.at("type").get<std::string>()).at("name");
            const std::string where = std::string(module.name) + " " + block_name;
            auto it = known_blocks().find(block_name);
            if (benchmark && it == known_blocks().end()) {
                // Its own set: the element struct is still the shared one where it names one.
                const json& member = types.at(resource.at("type").get<std::string>()).at("members")[0];
                if (is_struct_type(types, member.at("type")))
                    expect_struct_matches(types, member.at("type"), where);
                continue;
            }
            ASSERT_NE(it, known_blocks().end()) << where << ": not part of lightcuts/device/";
            seen.blocks.insert(block_name);
            const bool push_constant = resource.value("push_constant", false);
            EXPECT_EQ(push_constant, it->second.binding < 0) << where;
            if (!push_constant) {
                EXPECT_EQ(resource.at("set").get<int64_t>(), it->second.set) << where;
                EXPECT_EQ(resource.at("binding").get<int64_t>(), it->second.binding) << where;
            }
            expect_block_matches(types, resource, it->second, where);
        }
    }
    for (const char* kind : {"images", "textures"}) {
        if (!reflection.contains(kind) || benchmark) continue;
        for (const json& image : reflection.at(kind)) {
            const std::string name = image.at("name");
            const bool temporal = known_temporal_images().count(name) > 0;
            const auto& images = temporal ? known_temporal_images() : known_images();
            auto it = images.find(name);
            ASSERT_NE(it, images.end()) << module.name << ": image " << name;
            seen.images.insert(name);
            EXPECT_EQ(image.at("binding").get<uint32_t>(), it->second) << module.name << " " << name;
            EXPECT_EQ(image.value("set", 0u), temporal ? kTemporalSet : 0u) << module.name << " " << name;
        }
    }
    if (reflection.contains("specialization_constants")) {
        for (const json& constant : reflection.at("specialization_constants")) {
            const std::string name = constant.at("name");
            if (name.empty()) {
                // The workgroup size's, checked below.
                const uint32_t id = constant.at("id").get<uint32_t>();
                EXPECT_TRUE(id == kSpecWorkgroupX || id == kSpecWorkgroupY) << module.name;
                continue;
            }
            auto it = known_spec_constants().find(name);
            ASSERT_NE(it, known_spec_constants().end()) << module.name << ": " << name;
            seen.spec_constants.insert(name);
            EXPECT_EQ(constant.at("id").get<uint32_t>(), it->second) << module.name << " " << name;
        }
    }
    // Compute workgroup sizes come from kSpecWorkgroupX / kSpecWorkgroupY.
    for (const json& entry : reflection.at("entryPoints")) {
        if (entry.at("mode") != "comp") continue;
        const json& is_id = entry.at("workgroup_size_is_spec_constant_id");
        const json& size = entry.at("workgroup_size");
        ASSERT_TRUE(is_id[0].get<bool>() && is_id[1].get<bool>()) << module.name;
        EXPECT_EQ(size[0].get<uint32_t>(), kSpecWorkgroupX) << module.name;
        EXPECT_EQ(size[1].get<uint32_t>(), kSpecWorkgroupY) << module.name;
    }
}

TEST(ShaderInterface, EveryModuleMatchesTheSharedHeaders) {
    ASSERT_GT(std::size(kLcShaderModules), 0u);
    Seen seen;
    for (const LcShaderModule& module : kLcShaderModules) {
        SCOPED_TRACE(module.name);
        expect_module_matches(module, seen);
    }
    // The checks above ran on every block, image and constant of the interface.
    for (const auto& [name, block] : known_blocks()) EXPECT_TRUE(seen.blocks.count(name)) << name;
    for (const auto& [name, binding] : known_images()) EXPECT_TRUE(seen.images.count(name)) << name;
    for (const auto& [name, binding] : known_temporal_images())
        EXPECT_TRUE(seen.images.count(name)) << name;
    for (const auto& [name, id] : known_spec_constants())
        EXPECT_TRUE(seen.spec_constants.count(name)) << name;
}

TEST(ShaderInterface, FrameSetIsImagesThenBuffersWithoutGaps) {
    // renderer.cpp creates bindings 0..kFrameBindingCount-1 of the frame set,
    // storage images below kBindLeafLights and storage buffers from it on.
    std::vector<int> uses(kFrameBindingCount, 0);
    for (const auto& [name, binding] : known_images()) {
        if (name.ends_with("_texture")) continue;  // the G-buffer pass's material set
        ASSERT_LT(binding, kBindLeafLights) << name;
        ++uses[binding];
    }
    for (const auto& [name, block] : known_blocks()) {
        if (block.binding < 0 || block.set != 0) continue;  // push constants, other sets
        ASSERT_GE(block.binding, int64_t(kBindLeafLights)) << name;
        ASSERT_LT(block.binding, int64_t(kFrameBindingCount)) << name;
        ++uses[size_t(block.binding)];
    }
    for (uint32_t b = 0; b < kFrameBindingCount; ++b) EXPECT_EQ(uses[b], 1) << "binding " << b;
}

TEST(ShaderInterface, TemporalSetHasEveryBindingOnce) {
    // temporal_history.cpp creates bindings 0..kTemporalBindingCount-1: the
    // parameters' buffer and storage images.
    std::vector<int> uses(kTemporalBindingCount, 0);
    for (const auto& [name, binding] : known_temporal_images()) {
        ASSERT_LT(binding, kTemporalBindingCount) << name;
        ++uses[binding];
    }
    for (const auto& [name, block] : known_blocks()) {
        if (block.set != kTemporalSet || !block.layout.empty()) continue;
        ASSERT_LT(block.binding, int64_t(kTemporalBindingCount)) << name;
        ++uses[size_t(block.binding)];
    }
    for (uint32_t b = 0; b < kTemporalBindingCount; ++b) EXPECT_EQ(uses[b], 1) << "binding " << b;
}

}  // namespace
}  // namespace lc
