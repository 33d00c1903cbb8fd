#version 460
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// Lists the pixels whose paths a light transport kernel parked (parking/parking.glsl) in
// b_parked_list, with one atomic a workgroup on its length, and keeps the continuation kernel's
// indirect arguments at workgroups of 64 covering it.
layout(local_size_x = 1024) in;

layout(set = 0, binding = 0, std430) readonly buffer ParkedFlags { uint f[]; } b_parked_flags;
layout(set = 0, binding = 1, std430) writeonly buffer ParkedList { uint q[]; } b_parked_list;
layout(set = 0, binding = 2, std430) buffer ParkedCount { uint n; } b_parked_count;
layout(set = 0, binding = 3, std430) buffer ParkedArgs { uint groups; uint y; uint z; uint pad; } b_parked_args;

layout(push_constant) uniform Push { uint pixels; } push;

// One count a subgroup: 1024 invocations in subgroups of at least 4.
shared uint s_count[256];
shared uint s_base;

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool parked = i < push.pixels && b_parked_flags.f[i] != 0u;
    uvec4 ballot = subgroupBallot(parked);
    if (subgroupElect()) {
        s_count[gl_SubgroupID] = subgroupBallotBitCount(ballot);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        uint total = 0u;
        for (uint k = 0u; k < gl_NumSubgroups; ++k) {
            uint c = s_count[k];
            s_count[k] = total;
            total += c;
        }
        uint base = 0u;
        if (total > 0u) {
            base = atomicAdd(b_parked_count.n, total);
            uint groups = (base + total + 63u) / 64u - (base + 63u) / 64u;
            if (groups > 0u) {
                atomicAdd(b_parked_args.groups, groups);
            }
            b_parked_args.y = 1u;
            b_parked_args.z = 1u;
        }
        s_base = base;
    }
    barrier();
    if (parked) {
        b_parked_list.q[s_base + s_count[gl_SubgroupID] + subgroupBallotExclusiveBitCount(ballot)] = i;
    }
}
