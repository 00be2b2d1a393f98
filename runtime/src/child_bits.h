/* The set bits of a child mask (a byte: bit k for child k), lowest first, as a list read from a
 * table: private to runtime/src, for the octree walk's loops (octree_render.c).
 *
 * Promise:
 *   for (child_iter s = CHILDREN(m); s; s = NEXT_CHILD(s)) { const intptr_t k = CHILD(s); ... }
 *                     visits k over the set bits of m, lowest first.
 * With MC_LEAF_SWITCH (config.h) from child_seq[m], whose byte j (bits 8j..8j+7) holds 1 + the index
 * of the j-th lowest set bit of m, 0 past the last: a walk takes each child from the low byte, then
 * shifts, with no bit scan (2 KB of table, static: only a file that reads it holds it). Without it,
 * a bit scan each and no table. The table is built by the compiler from its definition, not written
 * out (tests/unit/test_bits.c checks every entry against a loop over the bits).
 */
#ifndef MODELC_CHILD_BITS_H
#define MODELC_CHILD_BITS_H

#include <stdint.h>

#include "modelc/bits.h"
#include "modelc/config.h"

#if MC_LEAF_SWITCH
/* Every mask's list, E(v, c) of it in the order of the masks: v the list right-aligned in 64 bits,
 * c its length. Bits are added from the highest, which varies slowest, down, each one's byte below
 * those of the c already set. */
#define MC_CB(b, v, c) ((v) + ((uint64_t)(b) << (8 * (7 - (c)))))
#define MC_CHILD_BYTES1(E, v, c) E(v, c), E(MC_CB(1, v, c), (c) + 1)
#define MC_CHILD_BYTES2(E, v, c) MC_CHILD_BYTES1(E, v, c), MC_CHILD_BYTES1(E, MC_CB(2, v, c), (c) + 1)
#define MC_CHILD_BYTES3(E, v, c) MC_CHILD_BYTES2(E, v, c), MC_CHILD_BYTES2(E, MC_CB(3, v, c), (c) + 1)
#define MC_CHILD_BYTES4(E, v, c) MC_CHILD_BYTES3(E, v, c), MC_CHILD_BYTES3(E, MC_CB(4, v, c), (c) + 1)
#define MC_CHILD_BYTES5(E, v, c) MC_CHILD_BYTES4(E, v, c), MC_CHILD_BYTES4(E, MC_CB(5, v, c), (c) + 1)
#define MC_CHILD_BYTES6(E, v, c) MC_CHILD_BYTES5(E, v, c), MC_CHILD_BYTES5(E, MC_CB(6, v, c), (c) + 1)
#define MC_CHILD_BYTES7(E, v, c) MC_CHILD_BYTES6(E, v, c), MC_CHILD_BYTES6(E, MC_CB(7, v, c), (c) + 1)
#define MC_CHILD_BYTES(E) MC_CHILD_BYTES7(E, (uint64_t)0, 0), MC_CHILD_BYTES7(E, MC_CB(8, (uint64_t)0, 0), 1)

/* the list moved down to byte 0, in two shifts (64 bits when no bit is set) */
#define MC_SEQ_ENTRY(v, c) ((v) >> 4 * (8 - (c)) >> 4 * (8 - (c)))
static const uint64_t child_seq[256] = { MC_CHILD_BYTES(MC_SEQ_ENTRY) };

typedef uint64_t child_iter;
#define CHILDREN(m) child_seq[m]
#define NEXT_CHILD(s) ((s) >> 8)
#define CHILD(s) ((intptr_t)((s) & 0xff) - 1)
#else
typedef unsigned child_iter;
#define CHILDREN(m) (m)
#define NEXT_CHILD(s) ((s) & ((s) - 1))
#define CHILD(s) ((intptr_t)mc_ctz(s))
#endif

#endif
