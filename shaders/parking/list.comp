#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// Lists the pixels whose paths a light transport kernel parked (parking/parking.glsl) in
// b_parked_list, in pixel order within a workgroup, with one atomic a workgroup on its length, and
// keeps the continuation kernel's indirect arguments at workgroups of 64 covering it. Each
// invocation reads the flags of eight pixels (at 1080p on an H200: 0.016-0.017 ms with one,
// 0.009-0.010 with four, 0.007-0.008 with eight, 0.009-0.011 with sixteen; bench/README.md).
layout(local_size_x = 1024) in;

// Pixels whose flags one invocation reads.
const uint FLAGS_PER_INVOCATION = 8u;

layout(set = 0, binding = 0, std430) readonly buffer ParkedFlags { uint f[]; } b_parked_flags;
layout(set = 0, binding = 1, std430) writeonly buffer ParkedList { uint q[]; } b_parked_list;
layout(set = 0, binding = 2, std430) buffer ParkedCount { uint n; } b_parked_count;
layout(set = 0, binding = 3, std430) buffer ParkedArgs { uint groups; uint y; uint z; uint pad; } b_parked_args;

layout(push_constant) uniform Push { uint pixels; } push;

// One count a subgroup: 1024 invocations in subgroups of at least 4.
shared uint s_count[256];
shared uint s_base;

void main() {
    uint first = FLAGS_PER_INVOCATION * gl_GlobalInvocationID.x;
    // Bit k: pixel first + k parked.
    uint parked = 0u;
    for (uint k = 0u; k < FLAGS_PER_INVOCATION; ++k) {
        if (first + k < push.pixels && b_parked_flags.f[first + k] != 0u) {
            parked |= 1u << k;
        }
    }
    uint count = bitCount(parked);
    uint before = subgroupExclusiveAdd(count);
    uint subgroup_total = subgroupAdd(count);
    if (subgroupElect()) {
        s_count[gl_SubgroupID] = subgroup_total;
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
    uint slot = s_base + s_count[gl_SubgroupID] + before;
    while (parked != 0u) {
        uint k = findLSB(parked);
        parked &= parked - 1u;
        b_parked_list.q[slot++] = first + k;
    }
}
