// The binary BVH layout's walks (lucid_engine::scene::gpu::bvh_pack): one 64-byte node per step
// holds both children's boxes and child words, the nearer child is taken, the farther stacked.
// Included by traverse.glsl (which defines the primitive and instance tests used here).
#ifndef LUCID_TRAVERSE_BINARY_GLSL
#define LUCID_TRAVERSE_BINARY_GLSL

// Far children a walk may stack: one per interior node of a path (the renderer refuses deeper
// trees: lucid_engine::scene::gpu::BvhLayout::max_depths).
const uint TLAS_STACK = 24u;
const uint BLAS_STACK = 40u;

// Child words: an interior node's index, or with BVH_LEAF set a leaf's first primitive (27 bits)
// and count - 1 (4 bits); BVH_EMPTY is an empty tree's root.
const uint BVH_LEAF = 0x80000000u;

uint leaf_first(uint word) {
    return word & 0x07ffffffu;
}

uint leaf_count(uint word) {
    return ((word >> 27u) & 15u) + 1u;
}

BvhNode unpack_binary_node(uvec4 a, uvec4 b, uvec4 c, uvec4 d) {
    BvhNode node;
    node.left_min = uintBitsToFloat(a.xyz);
    node.left = a.w;
    node.left_max = uintBitsToFloat(b.xyz);
    node.right = b.w;
    node.right_min = uintBitsToFloat(c.xyz);
    node.pad0 = c.w;
    node.right_max = uintBitsToFloat(d.xyz);
    node.pad1 = d.w;
    return node;
}

BvhNode blas_binary_node(uint index) {
    uint k = 4u * index;
    return unpack_binary_node(blas_word(k), blas_word(k + 1u), blas_word(k + 2u), blas_word(k + 3u));
}

BvhNode tlas_binary_node(uint index) {
    uint k = 4u * index;
    return unpack_binary_node(b_tlas.n[k], b_tlas.n[k + 1u], b_tlas.n[k + 2u], b_tlas.n[k + 3u]);
}

// Visits an interior node's children: returns the word of the nearer child the ray enters before
// t_max (BVH_EMPTY when neither), and in far_child the other one when both are entered (else
// BVH_EMPTY).
uint order_children(BvhNode node, vec3 scaled_origin, vec3 inv_dir, float t_max, out uint far_child) {
    float t_left = box_entry(node.left_min, node.left_max, scaled_origin, inv_dir, t_max);
    float t_right = box_entry(node.right_min, node.right_max, scaled_origin, inv_dir, t_max);
    far_child = BVH_EMPTY;
    if (min(t_left, t_right) == T_INFINITY) {
        return BVH_EMPTY;
    }
    bool left_first = t_left <= t_right;
    if (max(t_left, t_right) < T_INFINITY) {
        far_child = left_first ? node.right : node.left;
    }
    return left_first ? node.left : node.right;
}

// Traverses one instance's binary BLAS in object space. Updates hit when closer; with any_hit,
// stops at the first hit and returns true.
bool traverse_blas_binary(uint inst_index, Instance inst, vec3 o, vec3 d, bool any_hit, inout Hit hit) {
    vec3 inv_dir = safe_inverse(d);
    vec3 scaled_origin = o * inv_dir;
    uint stack[BLAS_STACK];
    uint sp = 0u;
    uint word = inst.blas_root;
    bool found = false;
    if (word == BVH_EMPTY) {
        return false;
    }
    while (true) {
        if ((word & BVH_LEAF) != 0u) {
            uint first = leaf_first(word);
            uint count = leaf_count(word);
            for (uint k = 0u; k < count; ++k) {
                if (intersect_primitive(inst_index, inst, first + k, o, d, hit)) {
                    found = true;
                    if (any_hit) {
                        return true;
                    }
                }
            }
        } else {
            uint far_child;
            uint near_child = order_children(blas_binary_node(word), scaled_origin, inv_dir, hit.t, far_child);
            if (near_child != BVH_EMPTY) {
                if (far_child != BVH_EMPTY && sp < BLAS_STACK) {
                    stack[sp++] = far_child;
                }
                word = near_child;
                continue;
            }
        }
        if (sp == 0u) {
            break;
        }
        word = stack[--sp];
    }
    return found;
}

// Occlusion walks of two rays (object space, t_max <= 0: none) through one instance's binary BLAS,
// one after the other in a single loop: a lane whose first walk ends goes on with its second at
// once rather than waiting for the subgroup's slowest first walk. Returns whether each ray is
// occluded.
bvec2 occluded_pair_blas_binary(uint inst_index, Instance inst, vec3 o0, vec3 d0, float t0, vec3 o1, vec3 d1,
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
    uint stack[BLAS_STACK];
    uint sp = 0u;
    uint word = inst.blas_root;
    while (true) {
        bool ended = false;
        if ((word & BVH_LEAF) != 0u) {
            uint first = leaf_first(word);
            uint count = leaf_count(word);
            for (uint k = 0u; k < count; ++k) {
                if (intersect_primitive(inst_index, inst, first + k, o, d, hit)) {
                    ended = true;
                    occluded = bvec2(!second || occluded.x, second);
                    break;
                }
            }
        } else {
            uint far_child;
            uint near_child = order_children(blas_binary_node(word), scaled_origin, inv_dir, hit.t, far_child);
            if (near_child != BVH_EMPTY) {
                if (far_child != BVH_EMPTY && sp < BLAS_STACK) {
                    stack[sp++] = far_child;
                }
                word = near_child;
                continue;
            }
        }
        if (!ended && sp > 0u) {
            word = stack[--sp];
            continue;
        }
        if (second || !(t1 > 0.0)) {
            break;
        }
        second = true;
        o = o1;
        d = d1;
        hit.t = t1;
        inv_dir = safe_inverse(d);
        scaled_origin = o * inv_dir;
        sp = 0u;
        word = inst.blas_root;
    }
    return occluded;
}

// Walks the binary TLAS from its root word and the BLAS of every instance reached.
bool trace_binary_tlas(uint word, vec3 origin, vec3 dir, bool any_hit, inout Hit hit) {
    vec3 inv_dir = safe_inverse(dir);
    vec3 scaled_origin = origin * inv_dir;
    uint stack[TLAS_STACK];
    uint sp = 0u;
    bool found = false;
    while (true) {
        if ((word & BVH_LEAF) != 0u) {
            uint first = leaf_first(word);
            uint count = leaf_count(word);
            for (uint k = 0u; k < count; ++k) {
                if (intersect_instance(first + k, origin, dir, any_hit, hit)) {
                    found = true;
                    if (any_hit) {
                        return true;
                    }
                }
            }
        } else {
            uint far_child;
            uint near_child = order_children(tlas_binary_node(word), scaled_origin, inv_dir, hit.t, far_child);
            if (near_child != BVH_EMPTY) {
                if (far_child != BVH_EMPTY && sp < TLAS_STACK) {
                    stack[sp++] = far_child;
                }
                word = near_child;
                continue;
            }
        }
        if (sp == 0u) {
            break;
        }
        word = stack[--sp];
    }
    return found;
}

#endif
