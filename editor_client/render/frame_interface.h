#pragma once
// The numbers C++ and the shaders share by convention: specialization-constant
// ids and the bindings of the compute passes' descriptor set.
#include <cstdint>

namespace lc::client {

// Specialization constant ids (shaders/effects.glsl, lightcuts.comp, cut_view.comp, gbuffer.frag).
enum SpecId : uint32_t {
    kSpecWorkgroupX = 0,
    kSpecWorkgroupY = 1,
    kSpecPointLights = 2,
    kSpecSpotLights = 3,
    kSpecDirectionalLights = 4,
    kSpecRangeWindow = 5,
    kSpecClassicLights = 6,
    kSpecEmissive = 7,
    kSpecCriterion = 8,  // lightcuts.comp: radius or bound
    kSpecCutView = 9,
    kSpecTextures = 10,
    kSpecErrorRatio = 11,  // lightcuts.comp, bound criterion (float bits)
    kSpecMaxCut = 12,      // lightcuts.comp, bound criterion: heap capacity
    kSpecBoundSearch = 13,  // lightcuts.comp: walk or heap (bound_walk.h)
    kSpecWalkMaxCut = 14,
    kSpecWalkMaxPasses = 15,
    kSpecWalkShrink = 16,  // float bits
    kSpecWalkMargin = 17,  // float bits
    kSpecWalkBisections = 18,
    kSpecShadows = 19,  // shadow_rays.glsl
    kSpecSpecular = 20,  // material_model.glsl
};

// Bindings of the compute passes' set (shaders/frame_bindings.glsl).
enum FrameBinding : uint32_t {
    kBindPosition = 0,
    kBindNormal = 1,
    kBindAlbedo = 2,
    kBindEmissive = 3,
    kBindHdr = 4,
    kBindCut = 5,
    kBindDisplay = 6,
    kBindLeafLights = 7,
    kBindTreeNodes = 8,
    kBindClassicLights = 9,
    kBindCounters = 10,
    kBindNodeBounds = 11,
    kBindBvhNodes = 12,
    kBindShadowTriangles = 13,
    kBindWalkStates = 14,
    kFrameBindingCount = 15,
};

}  // namespace lc::client
