#version 460
// Counts its invocations and workgroups into b_counter (the render graph's indirect-dispatch
// test, tests/tests/graph_gpu.rs): dispatched indirectly, they are what the arguments said.

layout(local_size_x = 32) in;

layout(set = 0, binding = 0) buffer Counter { uint invocations; uint groups_x; } b_counter;

void main() {
    atomicAdd(b_counter.invocations, 1u);
    if (gl_LocalInvocationIndex == 0u) {
        atomicMax(b_counter.groups_x, gl_NumWorkGroups.x);
    }
}
