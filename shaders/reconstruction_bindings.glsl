// Reconstruction cuts' own set (set kReconstructionSet, owned by
// ReconstructionPass): per sample a header and its lightcut's records, one a
// cut node in pre-order, at most kRecordCap; and the lattice of samples,
// every kBlock-th pixel of each row and column plus the last, so that every
// pixel lies in a block whose four corners are samples.
#ifndef LC_RECONSTRUCTION_BINDINGS_GLSL
#define LC_RECONSTRUCTION_BINDINGS_GLSL

#include "frame_bindings.glsl"

layout(constant_id = kSpecReconstructionBlock) const uint kBlock = 4u;
layout(constant_id = kSpecReconstructionCap) const uint kRecordCap = 512u;

layout(std430, set = 1, binding = kBindReconstructionSamples) buffer ReconstructionSamples {
    GpuReconstructionSample samples[];
};
layout(std430, set = 1, binding = kBindReconstructionRecords) buffer CutRecords { GpuCutRecords records[]; };

// Where sample s's records start, counted in records.
uint first_record_of(uint s) { return s * ((kRecordCap + 3u) / 4u) * 4u; }
uint read_record(uint slot) { return records[slot >> 2u].words[slot & 3u]; }

// Samples along each axis: 0, kBlock, 2 kBlock, ... and the last pixel.
uvec2 sample_lattice_size() {
    return uvec2((frame.width + kBlock - 2u) / kBlock + 1u, (frame.height + kBlock - 2u) / kBlock + 1u);
}

ivec2 sample_pixel(uvec2 sample_id) {
    return ivec2(min(sample_id * kBlock, uvec2(frame.width, frame.height) - 1u));
}

bool is_sample_pixel(ivec2 pixel) {
    bvec2 on_lattice = equal(uvec2(pixel) % kBlock, uvec2(0u));
    bvec2 last = equal(uvec2(pixel), uvec2(frame.width, frame.height) - 1u);
    return (on_lattice.x || last.x) && (on_lattice.y || last.y);
}

#endif
