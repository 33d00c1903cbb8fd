// The body of path_trace.comp and path_trace_in_workgroup.comp: the path tracer (path_trace.glsl)
// without the denoiser's images, or with them and one sample a pixel (ONE_SAMPLE), where the first
// hit's albedo and emission go straight to their images at the first hit and the path's end reads
// them back: 72 registers on `classroom` where path_trace_surfaces.comp, which keeps them for the
// running sums of more samples, takes 80, and 6% faster (bench/README.md).
#define PATH_KEEP_FIRST_ALBEDO(v) if (SURFACE_OUTPUTS && ONE_SAMPLE) { imageStore(u_albedo, ivec2(gl_GlobalInvocationID.xy), vec4((v), 1.0)); }
#define PATH_KEEP_FIRST_EMISSION(v) if (SURFACE_OUTPUTS && ONE_SAMPLE) { imageStore(u_emission, ivec2(gl_GlobalInvocationID.xy), vec4((v), 1.0)); }
#define PATH_FIRST_ALBEDO vec3(1.0)
#define PATH_FIRST_EMISSION vec3(0.0)
#include "path_trace/path_trace.glsl"
