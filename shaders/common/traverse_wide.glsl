// The compressed wide BVH layout's walks (lucid_engine::scene::gpu::wide, after Ylitie, Karras and
// Laine 2017): 80-byte nodes of up to 8 children with byte-quantized boxes. A step tests all
// children of a node at once into a hit mask: inner children at bits 24 + (slot ^ octant_inverse),
// so that popping the highest bit first visits them near to far (the packer put each child in the
// slot of the octant whose rays reach it first), and leaf primitives at bits 0-23 (their offsets
// from the node's primitive base). The stack holds node groups: the base of a node's inner
// children and its remaining hit bits with its inner mask in bits 0-7; at most one per level.
// Included by traverse.glsl (which defines the primitive and instance tests used here).
// lucid_engine::scene::gpu::wide::walk is this walk on the CPU, step for step.
#ifndef LUCID_TRAVERSE_WIDE_GLSL
#define LUCID_TRAVERSE_WIDE_GLSL

// Node groups a walk may stack: one per level below the root (the renderer refuses deeper trees:
// lucid_engine::scene::gpu::BvhLayout::max_depths).
const uint WIDE_STACK = 32u;

// 7 - the ray's octant (bit 0: x negative, bit 1: y, bit 2: z).
uint octant_inverse(vec3 d) {
    return (d.x < 0.0 ? 0u : 1u) | (d.y < 0.0 ? 0u : 2u) | (d.z < 0.0 ? 0u : 4u);
}

// The hit bits of four children (meta bytes `meta`, inner flags in the low 4 bits of `inner`)
// whose quantized near and far planes per axis are the bytes of near_q and far_q.
uint wide_hits4(uvec3 near_q, uvec3 far_q, uint meta, uint inner, vec3 adjusted_inv,
                vec3 adjusted_origin, uint oct_inv, float t_max) {
    const uvec4 shifts = uvec4(0u, 8u, 16u, 24u);
    vec4 enter = max(fma(vec4((uvec4(near_q.x) >> shifts) & 0xffu), vec4(adjusted_inv.x), vec4(adjusted_origin.x)),
                     fma(vec4((uvec4(near_q.y) >> shifts) & 0xffu), vec4(adjusted_inv.y), vec4(adjusted_origin.y)));
    enter = max(enter, max(fma(vec4((uvec4(near_q.z) >> shifts) & 0xffu), vec4(adjusted_inv.z), vec4(adjusted_origin.z)),
                           vec4(0.0)));
    vec4 leave = min(fma(vec4((uvec4(far_q.x) >> shifts) & 0xffu), vec4(adjusted_inv.x), vec4(adjusted_origin.x)),
                     fma(vec4((uvec4(far_q.y) >> shifts) & 0xffu), vec4(adjusted_inv.y), vec4(adjusted_origin.y)));
    leave = min(leave, min(fma(vec4((uvec4(far_q.z) >> shifts) & 0xffu), vec4(adjusted_inv.z), vec4(adjusted_origin.z)),
                           vec4(t_max)));
    uvec4 m = (uvec4(meta) >> shifts) & 0xffu;
    uvec4 is_inner = (uvec4(inner) >> uvec4(0u, 1u, 2u, 3u)) & 1u;
    uvec4 bits = (m >> 5u) << ((m & 31u) ^ (is_inner * oct_inv));
    uvec4 hits = mix(uvec4(0u), bits, lessThanEqual(enter, leave));
    return hits.x | hits.y | hits.z | hits.w;
}

// The hit mask of the wide node n0..n4 for the ray (scaled_origin = origin * inv_dir) within
// (0, t_max).
uint wide_hits(uvec4 n0, uvec4 n1, uvec4 n2, uvec4 n3, uvec4 n4, vec3 scaled_origin, vec3 inv_dir,
               uint oct_inv, float t_max) {
    uvec3 exponents = (uvec3(n0.w) >> uvec3(0u, 8u, 16u)) & 0xffu;
    vec3 adjusted_inv = uintBitsToFloat(exponents << 23u) * inv_dir;
    vec3 adjusted_origin = fma(uintBitsToFloat(n0.xyz), inv_dir, -scaled_origin);
    uint inner = n0.w >> 24u;
    // Per axis, both words of the lows and of the highs; the near plane is the low one where the
    // direction is positive.
    bvec3 positive = greaterThanEqual(inv_dir, vec3(0.0));
    uvec2 near_x = positive.x ? n2.xy : n3.zw;
    uvec2 far_x = positive.x ? n3.zw : n2.xy;
    uvec2 near_y = positive.y ? n2.zw : n4.xy;
    uvec2 far_y = positive.y ? n4.xy : n2.zw;
    uvec2 near_z = positive.z ? n3.xy : n4.zw;
    uvec2 far_z = positive.z ? n4.zw : n3.xy;
    return wide_hits4(uvec3(near_x.x, near_y.x, near_z.x), uvec3(far_x.x, far_y.x, far_z.x), n1.z,
                      inner, adjusted_inv, adjusted_origin, oct_inv, t_max)
         | wide_hits4(uvec3(near_x.y, near_y.y, near_z.y), uvec3(far_x.y, far_y.y, far_z.y), n1.w,
                      inner >> 4u, adjusted_inv, adjusted_origin, oct_inv, t_max);
}

// The node the next inner hit of `group` names (and that bit cleared).
uint wide_pop_child(inout uvec2 group, uint oct_inv) {
    uint bit = findMSB(group.y);
    group.y &= ~(1u << bit);
    uint slot = (bit - 24u) ^ oct_inv;
    return group.x + bitCount(group.y & ((1u << slot) - 1u));
}

// The group a walk starts from: the root as the one inner child of a virtual parent.
uvec2 wide_root_group(uint root, uint oct_inv) {
    return uvec2(root, (1u << (24u + oct_inv)) | 1u);
}

// Traverses one instance's wide BLAS in object space. Updates hit when closer; with any_hit, stops
// at the first hit and returns true.
bool traverse_blas_wide(uint inst_index, Instance inst, vec3 o, vec3 d, bool any_hit, inout Hit hit) {
    if (inst.blas_root == BVH_EMPTY) {
        return false;
    }
    vec3 inv_dir = safe_inverse(d);
    vec3 scaled_origin = o * inv_dir;
    uint oct_inv = octant_inverse(d);
    uvec2 stack[WIDE_STACK];
    uint sp = 0u;
    uvec2 group = wide_root_group(inst.blas_root, oct_inv);
    uvec2 prims = uvec2(0u);
    bool found = false;
    while (true) {
        while (prims.y != 0u) {
            uint k = findLSB(prims.y);
            prims.y &= prims.y - 1u;
            if (intersect_primitive(inst_index, inst, prims.x + k, o, d, hit)) {
                found = true;
                if (any_hit) {
                    return true;
                }
            }
        }
        if (group.y <= 0x00ffffffu) {
            if (sp == 0u) {
                break;
            }
            group = stack[--sp];
        }
        uint k = 5u * wide_pop_child(group, oct_inv);
        if (group.y > 0x00ffffffu && sp < WIDE_STACK) {
            stack[sp++] = group;
        }
        uvec4 n0 = blas_word(k);
        uvec4 n1 = blas_word(k + 1u);
        uint hits = wide_hits(n0, n1, blas_word(k + 2u), blas_word(k + 3u), blas_word(k + 4u),
                              scaled_origin, inv_dir, oct_inv, hit.t);
        group = uvec2(n1.x, (hits & 0xff000000u) | (n0.w >> 24u));
        prims = uvec2(n1.y, hits & 0x00ffffffu);
    }
    return found;
}

// Occlusion walks of two rays (object space, t_max <= 0: none) through one instance's wide BLAS,
// one after the other in a single loop: a lane whose first walk ends goes on with its second at
// once rather than waiting for the subgroup's slowest first walk, so that a subgroup takes the
// most steps of one lane's two walks together rather than the sum of each walk's most. Returns
// whether each ray is occluded.
bvec2 occluded_pair_blas_wide(uint inst_index, Instance inst, vec3 o0, vec3 d0, float t0, vec3 o1, vec3 d1,
                              float t1) {
    bvec2 occluded = bvec2(false);
    bool second = !(t0 > 0.0);
    if (inst.blas_root == BVH_EMPTY || (second && !(t1 > 0.0))) {
        return occluded;
    }
    vec3 o = second ? o1 : o0;
    vec3 d = second ? d1 : d0;
    Hit hit;
    hit.t = second ? t1 : t0;
    vec3 inv_dir = safe_inverse(d);
    vec3 scaled_origin = o * inv_dir;
    uint oct_inv = octant_inverse(d);
    uvec2 stack[WIDE_STACK];
    uint sp = 0u;
    uvec2 group = wide_root_group(inst.blas_root, oct_inv);
    uvec2 prims = uvec2(0u);
    while (true) {
        bool ended = false;
        while (prims.y != 0u) {
            uint k = findLSB(prims.y);
            prims.y &= prims.y - 1u;
            if (intersect_primitive(inst_index, inst, prims.x + k, o, d, hit)) {
                ended = true;
                occluded = bvec2(!second || occluded.x, second);
                break;
            }
        }
        if (!ended && group.y <= 0x00ffffffu) {
            ended = sp == 0u;
            if (!ended) {
                group = stack[--sp];
            }
        }
        if (ended) {
            if (second || !(t1 > 0.0)) {
                break;
            }
            second = true;
            o = o1;
            d = d1;
            hit.t = t1;
            inv_dir = safe_inverse(d);
            scaled_origin = o * inv_dir;
            oct_inv = octant_inverse(d);
            sp = 0u;
            group = wide_root_group(inst.blas_root, oct_inv);
            prims = uvec2(0u);
        }
        uint k = 5u * wide_pop_child(group, oct_inv);
        if (group.y > 0x00ffffffu && sp < WIDE_STACK) {
            stack[sp++] = group;
        }
        uvec4 n0 = blas_word(k);
        uvec4 n1 = blas_word(k + 1u);
        uint hits = wide_hits(n0, n1, blas_word(k + 2u), blas_word(k + 3u), blas_word(k + 4u),
                              scaled_origin, inv_dir, oct_inv, hit.t);
        group = uvec2(n1.x, (hits & 0xff000000u) | (n0.w >> 24u));
        prims = uvec2(n1.y, hits & 0x00ffffffu);
    }
    return occluded;
}

// Walks the wide TLAS from its root node and the BLAS of every instance reached.
bool trace_wide_tlas(uint root, vec3 origin, vec3 dir, bool any_hit, inout Hit hit) {
    vec3 inv_dir = safe_inverse(dir);
    vec3 scaled_origin = origin * inv_dir;
    uint oct_inv = octant_inverse(dir);
    uvec2 stack[WIDE_STACK];
    uint sp = 0u;
    uvec2 group = wide_root_group(root, oct_inv);
    uvec2 instances = uvec2(0u);
    bool found = false;
    while (true) {
        while (instances.y != 0u) {
            uint k = findLSB(instances.y);
            instances.y &= instances.y - 1u;
            if (intersect_instance(instances.x + k, origin, dir, any_hit, hit)) {
                found = true;
                if (any_hit) {
                    return true;
                }
            }
        }
        if (group.y <= 0x00ffffffu) {
            if (sp == 0u) {
                break;
            }
            group = stack[--sp];
        }
        uint k = 5u * wide_pop_child(group, oct_inv);
        if (group.y > 0x00ffffffu && sp < WIDE_STACK) {
            stack[sp++] = group;
        }
        uvec4 n0 = b_tlas.n[k];
        uvec4 n1 = b_tlas.n[k + 1u];
        uint hits = wide_hits(n0, n1, b_tlas.n[k + 2u], b_tlas.n[k + 3u], b_tlas.n[k + 4u],
                              scaled_origin, inv_dir, oct_inv, hit.t);
        group = uvec2(n1.x, (hits & 0xff000000u) | (n0.w >> 24u));
        instances = uvec2(n1.y, hits & 0x00ffffffu);
    }
    return found;
}

#endif
