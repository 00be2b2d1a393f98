/* The octree part of a baked model: what the generator emits and octree_render.h reads.
 *
 * An octree of depth D is stored level by level. Level l holds one entry per node at depth l, in
 * depth-first order (which, restricted to one level, is also left-to-right order). Each internal node
 * has a child-mask byte (bit k set = child k present; child k is offset by +-1/4 of the node's side
 * along x (bit 0), y (bit 1) and z (bit 2)). Each node at levels 1..D has a palette index.
 *
 * Because a level's entries are in depth-first order, a depth-first walk that keeps one read cursor
 * per level meets each level's entries exactly in stored order. So rendering at depth d <= D reads
 * the masks of levels 0..d-1 and the colours of level d, and nothing else: one baked model gives the
 * coarse image drawn while the view moves and the fine image drawn after.
 *
 * Every array is split into chunks (at most the generator's --chunk-bytes each) that may live in
 * different translation units (chunk.h); a chunk list ends with a {0, 0} sentinel. Chunks end only where the
 * renderer may cross them: mask chunks between sibling groups (the children of one node), colour
 * chunks between cousin groups (the grandchildren of one node), so the renderer checks for the end
 * of a chunk once per group instead of once per byte.
 */
#ifndef MODELC_OCTREE_H
#define MODELC_OCTREE_H

#include <stdint.h>
#include "config.h"
#include "chunk.h"

typedef struct mc_octree_level {
    uint32_t nodes;          /* nodes at this depth */
    const mc_chunk *masks;   /* child masks, one byte per node; NULL at the deepest level */
    const mc_chunk *colors;  /* palette index per node; NULL at level 0, and at every level of a
                              * monochrome octree (palette_size 1): every node is entry 0 */
} mc_octree_level;

typedef struct mc_octree {
    uint8_t depth;                   /* D: levels 0..D, leaves at D */
    uint16_t palette_size;           /* 1..256 */
    const uint8_t *palette;          /* palette_size RGB triplets */
    const mc_octree_level *levels;   /* D + 1 entries */
} mc_octree;

#endif
