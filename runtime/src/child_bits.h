/* The set bits of a child mask (a byte: bit k for child k), lowest first, as a list read from a
 * table: private to runtime/src, for the octree walk's loops (octree_render.c).
 *
 * Promise:
 *   for (child_iter s = CHILDREN(m); s; s = NEXT_CHILD(s)) { const intptr_t k = CHILD(s); ... }
 *                     visits k over the set bits of m, lowest first.
 * With MC_LEAF_SWITCH (config.h) from child_seq[m], whose slot j (MC_CHILD_BITS bits from bit
 * MC_CHILD_BITS * j) holds 1 + the index of the j-th lowest set bit of m, 0 past the last: a walk
 * takes each child from the low slot, then shifts, with no bit scan. Slots are bytes in 64 bits where
 * registers are 64 bits wide (2 KB of table), else nibbles in 32 bits (1 KB), so that the shift is
 * one instruction; MC_CHILD_BITS 4 or 8 chooses (tests build both). The table is static (only a file
 * that reads it holds it) and built by the compiler from its definition, not written out
 * (tests/unit/test_bits.c checks every entry against a loop over the bits). Without MC_LEAF_SWITCH,
 * a bit scan each and no table.
 */
#ifndef MODELC_CHILD_BITS_H
#define MODELC_CHILD_BITS_H

#include <stdint.h>

#include "modelc/bits.h"
#include "modelc/config.h"

#if MC_LEAF_SWITCH
#ifndef MC_CHILD_BITS
#if UINTPTR_MAX > 0xFFFFFFFFu
#define MC_CHILD_BITS 8
#else
#define MC_CHILD_BITS 4
#endif
#endif
#if MC_CHILD_BITS == 8
typedef uint64_t child_iter;
#elif MC_CHILD_BITS == 4
typedef uint32_t child_iter;
#else
#error "MC_CHILD_BITS must be 4 (nibbles in 32 bits) or 8 (bytes in 64 bits)"
#endif

/* Every mask's list, E(v, c) of it in the order of the masks: v the list right-aligned in 8 slots,
 * c its length. Bits are added from the highest, which varies slowest, down, each one's slot below
 * those of the c already set. */
#define MC_CB(b, v, c) ((v) + ((child_iter)(b) << (MC_CHILD_BITS * (7 - (c)))))
#define MC_CHILD_SLOTS1(E, v, c) E(v, c), E(MC_CB(1, v, c), (c) + 1)
#define MC_CHILD_SLOTS2(E, v, c) MC_CHILD_SLOTS1(E, v, c), MC_CHILD_SLOTS1(E, MC_CB(2, v, c), (c) + 1)
#define MC_CHILD_SLOTS3(E, v, c) MC_CHILD_SLOTS2(E, v, c), MC_CHILD_SLOTS2(E, MC_CB(3, v, c), (c) + 1)
#define MC_CHILD_SLOTS4(E, v, c) MC_CHILD_SLOTS3(E, v, c), MC_CHILD_SLOTS3(E, MC_CB(4, v, c), (c) + 1)
#define MC_CHILD_SLOTS5(E, v, c) MC_CHILD_SLOTS4(E, v, c), MC_CHILD_SLOTS4(E, MC_CB(5, v, c), (c) + 1)
#define MC_CHILD_SLOTS6(E, v, c) MC_CHILD_SLOTS5(E, v, c), MC_CHILD_SLOTS5(E, MC_CB(6, v, c), (c) + 1)
#define MC_CHILD_SLOTS7(E, v, c) MC_CHILD_SLOTS6(E, v, c), MC_CHILD_SLOTS6(E, MC_CB(7, v, c), (c) + 1)
#define MC_CHILD_SLOTS(E) MC_CHILD_SLOTS7(E, (child_iter)0, 0), MC_CHILD_SLOTS7(E, MC_CB(8, (child_iter)0, 0), 1)

/* the list moved down to slot 0, in two shifts (the whole width when no bit is set) */
#define MC_SEQ_ENTRY(v, c) ((v) >> MC_CHILD_BITS / 2 * (8 - (c)) >> MC_CHILD_BITS / 2 * (8 - (c)))
static const child_iter child_seq[256] = { MC_CHILD_SLOTS(MC_SEQ_ENTRY) };

#define CHILDREN(m) child_seq[m]
#define NEXT_CHILD(s) ((s) >> MC_CHILD_BITS)
#define CHILD(s) ((intptr_t)((s) & ((1u << MC_CHILD_BITS) - 1)) - 1)
#else
typedef unsigned child_iter;
#define CHILDREN(m) (m)
#define NEXT_CHILD(s) ((s) & ((s) - 1))
#define CHILD(s) ((intptr_t)mc_ctz(s))
#endif

#endif
