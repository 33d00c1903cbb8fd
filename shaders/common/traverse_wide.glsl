// The compressed wide BVH layout's walk (lucid_engine::scene::gpu::wide, after Ylitie, Karras and
// Laine 2017): 80-byte nodes of up to 8 children with byte-quantized boxes. A step tests all
// children of a node into a hit mask: inner children at bits 24 + (slot ^ octant_inverse),
// so that popping the highest bit first visits them near to far (the packer put each child in the
// slot of the octant whose rays reach it first), and leaf primitives at bits 0-23 (their offsets
// from the node's primitive base), tested before the next node. The TLAS and the BLAS of the
// instances it reaches are walked by one loop over one stack (the paper's two-level traversal):
// the stack holds node groups (the base of a node's inner children and its remaining hit bits,
// with its inner mask in bits 0-7), at most one per level, and groups of instances still to enter
// (their base and hit bits, all in bits 0-23). Included by traverse.glsl (which defines the
// primitive test used here). lucid_engine::scene::gpu::wide::walk is the walk of one tree on the
// CPU, step for step.
#ifndef LUCID_TRAVERSE_WIDE_GLSL
#define LUCID_TRAVERSE_WIDE_GLSL

// Groups the walk may stack: per level below the root at most one node group of the TLAS and then
// of an instance's BLAS, and the instances left of the TLAS node whose instance is being walked, so
// the TLAS's and the deepest BLAS's depths together (the renderer refuses deeper trees:
// lucid_engine::scene::gpu::BvhLayout::max_depths).
const uint WIDE_STACK = 40u;

// 7 - the ray's octant (bit 0: x negative, bit 1: y, bit 2: z).
uint octant_inverse(vec3 d) {
    return (d.x < 0.0 ? 0u : 1u) | (d.y < 0.0 ? 0u : 2u) | (d.z < 0.0 ? 0u : 4u);
}

// The hit bit of one child: its quantized near and far planes per axis are byte `lane` of near_q
// and far_q, its meta byte that of `meta`, bit `lane` of `inner` says whether it is an inner
// child. Tested on its own (entry, then exit, then the bit) rather than four children per step, so
// that fewer decoded values are live at once.
uint wide_hit(uvec3 near_q, uvec3 far_q, uint meta, uint inner, uint lane, vec3 adjusted_inv,
              vec3 adjusted_origin, uint oct_inv, float t_max) {
    uint shift = 8u * lane;
    uvec3 near_b = (near_q >> shift) & 0xffu;
    float enter = max(max(fma(float(near_b.x), adjusted_inv.x, adjusted_origin.x),
                          fma(float(near_b.y), adjusted_inv.y, adjusted_origin.y)),
                      max(fma(float(near_b.z), adjusted_inv.z, adjusted_origin.z), 0.0));
    uvec3 far_b = (far_q >> shift) & 0xffu;
    float leave = min(min(fma(float(far_b.x), adjusted_inv.x, adjusted_origin.x),
                          fma(float(far_b.y), adjusted_inv.y, adjusted_origin.y)),
                      min(fma(float(far_b.z), adjusted_inv.z, adjusted_origin.z), t_max));
    uint m = (meta >> shift) & 0xffu;
    uint is_inner = (inner >> lane) & 1u;
    uint bit = (m >> 5u) << ((m & 31u) ^ (is_inner * oct_inv));
    return enter <= leave ? bit : 0u;
}

// The hit bits of four children (meta bytes `meta`, inner flags in the low 4 bits of `inner`)
// whose quantized near and far planes per axis are the bytes of near_q and far_q.
uint wide_hits4(uvec3 near_q, uvec3 far_q, uint meta, uint inner, vec3 adjusted_inv,
                vec3 adjusted_origin, uint oct_inv, float t_max) {
    return wide_hit(near_q, far_q, meta, inner, 0u, adjusted_inv, adjusted_origin, oct_inv, t_max)
         | wide_hit(near_q, far_q, meta, inner, 1u, adjusted_inv, adjusted_origin, oct_inv, t_max)
         | wide_hit(near_q, far_q, meta, inner, 2u, adjusted_inv, adjusted_origin, oct_inv, t_max)
         | wide_hit(near_q, far_q, meta, inner, 3u, adjusted_inv, adjusted_origin, oct_inv, t_max);
}

// The hit mask of the wide node n0..n4 for the ray from o with reciprocal direction inv_dir within
// (0, t_max).
uint wide_hits(uvec4 n0, uvec4 n1, uvec4 n2, uvec4 n3, uvec4 n4, vec3 o, vec3 inv_dir,
               uint oct_inv, float t_max) {
    uvec3 exponents = (uvec3(n0.w) >> uvec3(0u, 8u, 16u)) & 0xffu;
    vec3 adjusted_inv = uintBitsToFloat(exponents << 23u) * inv_dir;
    vec3 adjusted_origin = fma(uintBitsToFloat(n0.xyz), inv_dir, -(o * inv_dir));
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

// Wide node `index` (five uvec4) of the bottom levels' buffer (blas) or of the top level's.
void wide_node(bool blas, uint index, out uvec4 n0, out uvec4 n1, out uvec4 n2, out uvec4 n3,
               out uvec4 n4) {
    uint k = 5u * index;
    if (blas) {
        n0 = b_blas.n[k];
        n1 = b_blas.n[k + 1u];
        n2 = b_blas.n[k + 2u];
        n3 = b_blas.n[k + 3u];
        n4 = b_blas.n[k + 4u];
    } else {
        n0 = b_tlas.n[k];
        n1 = b_tlas.n[k + 1u];
        n2 = b_tlas.n[k + 2u];
        n3 = b_tlas.n[k + 3u];
        n4 = b_tlas.n[k + 4u];
    }
}

// blas_sp while the walk is in the top level.
const uint WIDE_TOP_LEVEL = 0xffffffffu;

// The wide walk of trace_ray: from the TLAS root node `root`, or with SINGLE_INSTANCE from
// instance 0's BLAS, in one loop over one stack. A leaf child of the top level names instances:
// entering one stacks what is left of the top level (the node group, then the remaining
// instances), transforms the ray into object space and walks the instance's BLAS on top; when the
// stack falls back to the height it had on entry (blas_sp), the instance is done and the world-space
// ray comes back. Updates hit when closer; with any_hit, stops at the first hit. Returns whether
// hit names a primitive (hit.instance starts as 0xffffffff).
bool trace_wide(uint root, vec3 origin, vec3 dir, bool any_hit, inout Hit hit) {
    vec3 o = origin;
    vec3 d = dir;
    uint inst_index = 0u;
    uint inst_kind = INSTANCE_FLATTENED;
    uint blas_sp = WIDE_TOP_LEVEL;
    if (SINGLE_INSTANCE) {
        // A flattened instance is in world space; any other keeps its transform (a dynamic one).
        Instance inst = b_instances.i[0];
        if (inst.blas_root == BVH_EMPTY) {
            return false;
        }
        root = inst.blas_root;
        inst_kind = inst.kind;
        if (inst.kind != INSTANCE_FLATTENED) {
            o = transform_point(inst.world_to_object, origin);
            d = transform_vector(inst.world_to_object, dir);
        }
        blas_sp = 0u;
    }
    vec3 inv_dir = safe_inverse(d);
    uint oct_inv = octant_inverse(d);
    uvec2 stack[WIDE_STACK];
    uint sp = 0u;
    uvec2 group = wide_root_group(root, oct_inv);
    uvec2 leaves = uvec2(0u);
    while (true) {
        while (leaves.y != 0u) {
            uint leaf = leaves.x + findLSB(leaves.y);
            leaves.y &= leaves.y - 1u;
            if (SINGLE_INSTANCE || blas_sp != WIDE_TOP_LEVEL) {
                if (intersect_primitive(inst_index, inst_kind, leaf, o, d, hit) && any_hit) {
                    return true;
                }
                continue;
            }
            uint blas_root = b_instances.i[leaf].blas_root;
            if (blas_root == BVH_EMPTY) {
                continue;
            }
            if (group.y > 0x00ffffffu && sp < WIDE_STACK) {
                stack[sp++] = group;
            }
            if (leaves.y != 0u && sp < WIDE_STACK) {
                stack[sp++] = leaves;
            }
            blas_sp = sp;
            inst_index = leaf;
            inst_kind = b_instances.i[leaf].kind;
            o = transform_point(b_instances.i[leaf].world_to_object, origin);
            d = transform_vector(b_instances.i[leaf].world_to_object, dir);
            inv_dir = safe_inverse(d);
            oct_inv = octant_inverse(d);
            group = wide_root_group(blas_root, oct_inv);
            leaves.y = 0u;
        }
        if (group.y <= 0x00ffffffu) {
            if (sp == 0u) {
                break;
            }
            if (!SINGLE_INSTANCE && sp == blas_sp) {
                // The instance is done: back to the top level.
                blas_sp = WIDE_TOP_LEVEL;
                o = origin;
                d = dir;
                inv_dir = safe_inverse(d);
                oct_inv = octant_inverse(d);
            }
            group = stack[--sp];
            if (group.y <= 0x00ffffffu) {
                // The instances left of a top-level node.
                leaves = group;
                continue;
            }
        }
        uint child = wide_pop_child(group, oct_inv);
        if (group.y > 0x00ffffffu && sp < WIDE_STACK) {
            stack[sp++] = group;
        }
        uvec4 n0, n1, n2, n3, n4;
        wide_node(SINGLE_INSTANCE || blas_sp != WIDE_TOP_LEVEL, child, n0, n1, n2, n3, n4);
        uint hits = wide_hits(n0, n1, n2, n3, n4, o, inv_dir, oct_inv, hit.t);
        group = uvec2(n1.x, (hits & 0xff000000u) | (n0.w >> 24u));
        leaves = uvec2(n1.y, hits & 0x00ffffffu);
    }
    return hit.instance != 0xffffffffu;
}

#endif
