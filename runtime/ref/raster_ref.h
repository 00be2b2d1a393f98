/* Double-precision reference of the triangle rasterizer (modelc/raster.h), for tests only: never
 * linked into a viewer or firmware. It tests every pixel of the target on its own, with the rule
 * written out geometrically rather than as the runtime's row spans:
 *   - a centre p is inside when each edge's line has p strictly on the side of the opposite corner;
 *     on an edge's line, p counts for that edge when the edge is a top edge (horizontal, opposite
 *     corner below) or a left edge (not horizontal, opposite corner to the right of its line);
 *   - depth is the exact plane through the corners at p (barycentric weights, doubles).
 * Edge functions of these integer inputs (|x|, |y| <= 2^22) are exact in double. Corners beyond
 * MC_RASTER_COORD_LIMIT, zero-area triangles and, with MC_RASTER_CULL_BACK, back faces cover
 * nothing; z above MC_DEPTH_EMPTY - 2 is taken as MC_DEPTH_EMPTY - 2, as the runtime does. */
#ifndef MODELC_RASTER_REF_H
#define MODELC_RASTER_REF_H

#include <stdint.h>
#include <modelc/raster.h>

/* For a width x height target: covered[i] = 1 where pixel i (row-major) is covered, else 0, and
 * depth[i] the exact plane depth there (untouched elsewhere). Returns the number covered. */
uint32_t mc_raster_ref_triangle(unsigned width, unsigned height, const mc_raster_vertex v[3], unsigned flags,
                                uint8_t *covered, double *depth);

#endif
