#version 460
// Writes a VkDispatchIndirectCommand of `groups` x 1 x 1 workgroups at word `at` of b_args (the
// render graph's indirect-dispatch test, tests/tests/graph_gpu.rs).

layout(local_size_x = 1) in;

layout(set = 0, binding = 0) writeonly buffer Args { uint a[]; } b_args;

layout(push_constant) uniform Push { uint groups; uint at; } push;

void main() {
    b_args.a[push.at] = push.groups;
    b_args.a[push.at + 1u] = 1u;
    b_args.a[push.at + 2u] = 1u;
}
