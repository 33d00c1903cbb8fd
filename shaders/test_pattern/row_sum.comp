#version 460
// One invocation per row: sums the red channel of the row into b_sums.values[row].
layout(local_size_x = 64) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_in;
layout(set = 0, binding = 1) writeonly buffer RowSums {
    float values[];
} b_sums;

void main() {
    int row = int(gl_GlobalInvocationID.x);
    ivec2 size = imageSize(u_in);
    if (row >= size.y) {
        return;
    }
    float sum = 0.0;
    for (int x = 0; x < size.x; ++x) {
        sum += imageLoad(u_in, ivec2(x, row)).r;
    }
    b_sums.values[row] = sum;
}
