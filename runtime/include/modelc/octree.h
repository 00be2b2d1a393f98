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
 *
 * Normal cones (optional, levels 1..D-3, one 7-byte record per node in the level's order): int8
 * ax, ay, az, an axis about 127 long; uint8 s >= sin(theta) |a| rounded up, theta the largest angle
 * between the axis and the outward normal of any face the node's cube meets (so of any surface its
 * leaves sample), s = 255 where the normals span more than a half-space; then uint8 n2 and uint16
 * n3 (little-endian), the nodes of its subtree two and three levels below it (at most 64 and 512),
 * so that a walk drawing three levels below it steps over the subtree in constant time. A view
 * direction w (unit, towards the viewer, in model axes) sees only the backs of the node's surface
 * when a . w < -s. Chunks hold whole records.
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
    const mc_chunk *cones;   /* normal cone per node, 7 bytes (above); NULL where the bake has none */
} mc_octree_level;

typedef struct mc_octree {
    uint8_t depth;                   /* D: levels 0..D, leaves at D */
    uint16_t palette_size;           /* 1..256 */
    const uint8_t *palette;          /* palette_size RGB triplets */
    const mc_octree_level *levels;   /* D + 1 entries */
} mc_octree;

#endif
