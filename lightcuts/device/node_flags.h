// How every form of a light-tree node marks itself, written once for C++ and
// GLSL: the build node and the float node (lightcuts/tree/node_flags.h), the
// wire records (protocol/channel_records.cpp) and GpuTreeNode (gpu_structs.h)
// carry the same flag bits and mean "no child" and "unbounded" by the same values.
#ifndef LC_DEVICE_NODE_FLAGS_H
#define LC_DEVICE_NODE_FLAGS_H

#include "lightcuts/device/glsl_compat.h"

LC_DEVICE_BEGIN

// Joins trees of different light types (the paper keeps one tree per type):
// always refined, never a cluster.
LC_CONST uint kNodeMixedTypes = 1u;
// Every light below is bounced light (SceneLight::indirect): clamped, and
// skipped as a whole when indirect light is left out.
LC_CONST uint kNodeIndirect = 2u;
// Every light below is a radiosity patch (SceneLight::patch), with
// kNodeIndirect: a disk, never clamped.
LC_CONST uint kNodePatch = 4u;
// GpuTreeNode only. The representative has a range (> 0): the bounds read its
// position and range. Clear: the node is unbounded, and a bound need not load the light.
LC_CONST uint kNodeBoundedRepresentative = 8u;
// GpuTreeNode::flags and the wire's FLightData.light_flags: the node's
// LightType from this bit on.
LC_CONST uint kNodeTypeShift = 8u;

// A child index where a node has none (a leaf has neither); the walk form's
// first_child of a leaf.
LC_CONST int kNoChild = -1;
// The influence radius of a node that reaches everywhere (no range, a
// directional light, or a child that is unbounded).
LC_CONST float kUnboundedRadius = -1.0f;

LC_DEVICE_END

#endif
