// The kinds of material (lucid_engine::scene::gpu's material kinds), as BsdfParams and the scene's
// materials name them.
#ifndef LUCID_MATERIAL_KINDS_GLSL
#define LUCID_MATERIAL_KINDS_GLSL

const uint MATERIAL_DIFFUSE = 0u;
const uint MATERIAL_CONDUCTOR = 1u;
const uint MATERIAL_DIELECTRIC = 2u;
const uint MATERIAL_METAL_ROUGH = 3u;

#endif
