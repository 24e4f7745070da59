// Descriptor binding numbers, written once for the C++ that creates the
// descriptor sets and the shaders that declare them.
#ifndef LC_DEVICE_BINDINGS_H
#define LC_DEVICE_BINDINGS_H

#include "lightcuts/device/glsl_compat.h"

LC_DEVICE_BEGIN

// The compute passes' set (shaders/frame_bindings.glsl): storage images first,
// then storage buffers from kBindLeafLights on.
LC_CONST uint kBindPosition = 0u;  // G-buffer, w: 1 = geometry
LC_CONST uint kBindNormal = 1u;    // G-buffer, w: roughness
LC_CONST uint kBindAlbedo = 2u;    // G-buffer, w: metallic
LC_CONST uint kBindEmissive = 3u;  // G-buffer
LC_CONST uint kBindHdr = 4u;       // linear radiance
LC_CONST uint kBindCut = 5u;       // x: cut size, y: cut hash
LC_CONST uint kBindDisplay = 6u;   // sRGB-encoded
LC_CONST uint kBindLeafLights = 7u;
LC_CONST uint kBindTreeNodes = 8u;
LC_CONST uint kBindClassicLights = 9u;
LC_CONST uint kBindCounters = 10u;
LC_CONST uint kBindBvhNodes = 11u;
LC_CONST uint kBindShadowTriangles = 12u;
LC_CONST uint kBindWalkStates = 13u;
LC_CONST uint kBindBackground = 14u;         // GpuBackground, rewritten every frame
LC_CONST uint kBindEnvironmentTexels = 15u;  // GpuEnvironmentTexel, row 0 at the zenith
// Alpha-masked shadow triangles (lightcuts/alpha_mask.h): their texture
// coordinates, their masks, and the masks' texels (a word holds four).
LC_CONST uint kBindMaskedTriangles = 16u;
LC_CONST uint kBindAlphaMasks = 17u;
LC_CONST uint kBindMaskTexels = 18u;
LC_CONST uint kBindVplVisibility = 19u;  // GpuVisibilityBits, reference mode's exact clamp
LC_CONST uint kFrameBindingCount = 20u;

// The real-time mode's own set (set 1, shaders/temporal_bindings.glsl): the
// accumulated history and the positions it was shaded at, the previous frame's
// and this frame's (two of each, swapped every frame), and its parameters.
LC_CONST uint kTemporalSet = 1u;
LC_CONST uint kBindHistoryIn = 0u;           // rgb: accumulated radiance, a: frames in it
LC_CONST uint kBindHistoryOut = 1u;
LC_CONST uint kBindHistoryPositionIn = 2u;   // xyz: world position, w = 1 on geometry
LC_CONST uint kBindHistoryPositionOut = 3u;
LC_CONST uint kBindTemporalParams = 4u;      // GpuTemporalParams
LC_CONST uint kTemporalBindingCount = 5u;

// The real-time mode's light-draw records (set 2, owned by RealtimePass,
// shaders/realtime_lighting.comp): GpuDrawPair per tree node, made when the tree is.
LC_CONST uint kDrawPairSet = 2u;
LC_CONST uint kBindDrawPairs = 0u;

// Reconstruction cuts' own set (set 1 of ReconstructionPass's layout,
// shaders/reconstruction_bindings.glsl): per sample its header and its cut's records.
LC_CONST uint kReconstructionSet = 1u;
LC_CONST uint kBindReconstructionSamples = 0u;  // GpuReconstructionSample
LC_CONST uint kBindReconstructionRecords = 1u;  // GpuCutRecords, record_cap per sample (rounded up to 4)
LC_CONST uint kReconstructionBindingCount = 2u;

// Primary visibility by rays (set 1 of PrimaryRaysPass's layout,
// shaders/primary_rays.comp): a BVH over every triangle, each triangle's
// vertices and draw, the scene's vertices, the draws' materials, the eye rays.
LC_CONST uint kPrimarySet = 1u;
LC_CONST uint kBindPrimaryNodes = 0u;      // GpuBvhNode
LC_CONST uint kBindPrimaryTriangles = 1u;  // GpuShadowTriangle
LC_CONST uint kBindPrimarySources = 2u;    // GpuPrimaryTriangle, in the BVH's order
LC_CONST uint kBindSceneVertices = 3u;     // GpuVertex as 16 floats
LC_CONST uint kBindSurfaceMaterials = 4u;  // GpuSurfaceMaterial per draw
LC_CONST uint kBindPrimaryParams = 5u;     // GpuPrimaryParams
LC_CONST uint kPrimaryBindingCount = 6u;

// The G-buffer pass's material set (shaders/gbuffer.frag): combined image samplers.
LC_CONST uint kBindBaseColorTexture = 0u;
LC_CONST uint kBindEmissiveTexture = 1u;
LC_CONST uint kBindMetallicRoughnessTexture = 2u;  // linear: G, B
LC_CONST uint kBindNormalTexture = 3u;             // linear: tangent-space normal
LC_CONST uint kMaterialBindingCount = 4u;

LC_DEVICE_END

#endif
