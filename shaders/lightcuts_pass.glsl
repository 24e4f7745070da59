// What the three lightcuts passes share (lightcuts_radius.comp,
// lightcuts_bound_walk.comp, lightcuts_bound_heap.comp): per pixel a cut of
// the light tree, each cut node evaluated as a cluster (its representative's
// position, direction, range and spot cone with the cluster's RGB intensity;
// the bound criterion's passes may draw the representative per pixel:
// pixel_representative.glsl's cluster_light),
// classic lights added one by one.
#ifndef LC_LIGHTCUTS_PASS_GLSL
#define LC_LIGHTCUTS_PASS_GLSL

#extension GL_KHR_shader_subgroup_vote : require

#include "cut_hash.glsl"
#include "lighting_pass.glsl"
#include "pixel_representative.glsl"

layout(local_size_x_id = kSpecWorkgroupX, local_size_y_id = kSpecWorkgroupY) in;

struct Cut {
    vec3 radiance;  // sum over cut nodes of f_r * I_C * color * G * V
    uint size;
    uint hash;
    IndirectSums indirect;  // its indirect nodes, for the clamp
};

Cut empty_cut() { return Cut(vec3(0.0), 0u, 0u, no_indirect_sums()); }

void add_to_cut(inout Cut cut, uint node_index, GpuTreeNode node, SurfacePoint p) {
    vec3 contribution = light_radiance(cluster_light(int(node_index), node, p), p);
    cut.radiance += contribution;
    tally_indirect(cut.indirect, node.flags, node.first_child == kNoChild, contribution);
    cut.size += 1u;
    cut.hash += cut_hash_term(node_index);
}

#endif
