#version 460
// Reconstruction cuts, first dispatches (Walter et al. 2005, Sec. 7): the
// bound criterion's walk search (bound_walk.glsl) at every sample of the
// lattice (reconstruction_bindings.glsl), the same search and dispatches as
// lightcuts_bound_walk.comp, which also stores the sample's own pixel. Each
// shaded pass writes its cut's nodes as records in pre-order, with what each
// node's shadow ray said (kSeen*); the cut the search keeps is the last one
// written unless a later shaded pass went over max-cut (kWalkRecordsStale).
// A sample whose records do not hold its whole kept cut (over kRecordCap,
// stale, cut short by the loop limit, or no geometry) is not usable: the
// pixels of its blocks run lightcuts of their own. A cut stopped by max-cut
// before the rule was met is usable, with the error ratio it reached: with
// many lights of mixed types most samples stop there, and their pixels would
// otherwise all fall back to lightcuts that stop there too.
#extension GL_GOOGLE_include_directive : require

#define LC_WALK_RECORDS
#include "bound_criterion.glsl"
#include "reconstruction_bindings.glsl"

uint g_sample = 0u;  // this invocation's sample, row-major over the lattice

void record_cut_node(uint position, uint node, uint seen) {
    uint slot = first_record_of(g_sample) + position;
    if (position < kRecordCap) records[slot >> 2u].words[slot & 3u] = (node << kSeenBits) | seen;
}

void finish_sample(vec3 radiance, uint record_count, bool complete, float reached_ratio) {
    bool usable = complete && record_count <= kRecordCap;
    samples[g_sample] =
        GpuReconstructionSample(radiance, record_count, usable ? kSampleUsable : 0u, reached_ratio, 0u, 0u);
}

#include "bound_walk.glsl"

void main() {
    uvec2 lattice = sample_lattice_size();
    uvec2 id = gl_GlobalInvocationID.xy;
    if (id.x >= lattice.x || id.y >= lattice.y) return;
    g_sample = id.y * lattice.x + id.x;
    bound_walk_dispatch(sample_pixel(id));
}
