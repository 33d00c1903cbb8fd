// A small scene's BLAS nodes (either layout) and triangle records in workgroup memory: a shader that
// defines SCENE_IN_WORKGROUP calls scene_to_workgroup at the start of main, in uniform control flow,
// and its walks then read nodes and triangles there rather than from b_blas and b_triangles (on an
// H200 the Cornell box's path tracer takes 10% less time, bench/README.md). The workgroup memory
// is declared even where the sizes are 0, and the NVIDIA driver then runs some kernels slower
// (the path tracer on `classroom` 2.7%), so the path tracer comes in two shaders
// (path_trace_in_workgroup.comp is the one that defines it). The renderer sets the
// sizes only for a scene that fits (lucid_passes::plumbing::scene_buffers::workgroup_scene_words);
// with sizes 0, and in shaders that do not define SCENE_IN_WORKGROUP, the walks read the buffers.
// Included by traverse.glsl; requires scene.glsl.
#ifndef LUCID_WORKGROUP_SCENE_GLSL
#define LUCID_WORKGROUP_SCENE_GLSL

// The 16-byte words of b_blas and b_triangles copied, every one of each (0: none).
layout(constant_id = 128) const uint WORKGROUP_BLAS_WORDS = 0u;
layout(constant_id = 129) const uint WORKGROUP_TRIANGLE_WORDS = 0u;

#ifdef SCENE_IN_WORKGROUP
shared uvec4 s_blas[WORKGROUP_BLAS_WORDS + 1u];
shared vec4 s_triangles[WORKGROUP_TRIANGLE_WORDS + 1u];

// Copies the scene's BLAS nodes and triangle records into workgroup memory, `invocations` at a
// time (the workgroup's size), where the constants ask for it.
void scene_to_workgroup(uint invocations) {
    if (WORKGROUP_BLAS_WORDS > 0u) {
        for (uint i = gl_LocalInvocationIndex; i < WORKGROUP_BLAS_WORDS; i += invocations) {
            s_blas[i] = b_blas.n[i];
        }
        for (uint i = gl_LocalInvocationIndex; i < WORKGROUP_TRIANGLE_WORDS; i += invocations) {
            s_triangles[i] = b_triangles.t[i];
        }
        barrier();
    }
}
#else
// Nothing to copy: this shader reads the buffers.
void scene_to_workgroup(uint invocations) {
}
#endif

// The k-th 16-byte word of the BLAS nodes (either layout).
uvec4 blas_word(uint k) {
#ifdef SCENE_IN_WORKGROUP
    if (WORKGROUP_BLAS_WORDS > 0u) {
        return s_blas[k];
    }
#endif
    return b_blas.n[k];
}

// Triangle tri's first vertex and edges (lucid_engine::scene::gpu::GpuTriangle): the first two
// words of its record and the third's first float.
void triangle_edges(uint tri, out vec4 a, out vec4 b, out float c) {
    uint f = 3u * tri;
#ifdef SCENE_IN_WORKGROUP
    if (WORKGROUP_TRIANGLE_WORDS > 0u) {
        a = s_triangles[f];
        b = s_triangles[f + 1u];
        c = s_triangles[f + 2u].x;
        return;
    }
#endif
    a = b_triangles.t[f];
    b = b_triangles.t[f + 1u];
    c = b_triangles.t[f + 2u].x;
}

#endif
