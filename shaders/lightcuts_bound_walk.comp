#version 460
// Lightcuts with the bound criterion, walk search (the default;
// lightcuts/cuts/bound_walk.h): threshold passes, each a pre-order walk shared by
// the subgroup like the radius walk, refining every node whose error bound
// exceeds the pass's threshold; passes stop once every bound on the cut is
// <= error x the cut's total, the cut would exceed max-cut (the pixel keeps
// the previous pass's cut and counts in counters.max_cut_hits) or the passes
// run out. A pass that llvmpipe's loop limit cuts short runs again in the
// next dispatch, the search kept per pixel in walk_states between them.
// Mirrors bound_walk_cut() in bound_walk.cpp. With kWalkShareCuts the lanes
// of a subgroup (neighbouring pixels) share one cut: a node is refined when
// its bound exceeds the threshold of any lane still walking, so in each pass
// a lane's cut refines at least as far as its own at that threshold, and
// every lane shades the same node and traces its ray to the same light in
// the same step. Each lane still stops under its own rule (a finer cut may
// meet it a pass earlier). A lane whose shared pass exceeds max-cut leaves
// the vote (kWalkAlone) and walks that threshold again on its own: the
// nodes its neighbours need must not push it over the cap, where it would
// bisect down to a cut coarser than its own.
#extension GL_GOOGLE_include_directive : require

#include "bound_walk.glsl"

// With shared cuts (on 8x8 workgroups: Renderer::validate), a subgroup of 8
// lanes covers a 4x2 block of pixels instead of a row of 8: closer points,
// so a shared cut refines less far beyond each pixel's own.
ivec2 pixel_of_invocation() {
    if (!kWalkShareCuts) return ivec2(gl_GlobalInvocationID.xy);
    uint i = gl_LocalInvocationIndex;
    uvec2 local = uvec2(((i >> 3u) & 1u) * 4u + (i & 3u), (i >> 4u) * 2u + ((i >> 2u) & 1u));
    return ivec2(gl_WorkGroupID.xy * 8u + local);
}

void main() {
    ivec2 pixel = pixel_of_invocation();
    if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
    bound_walk_dispatch(pixel);
}
