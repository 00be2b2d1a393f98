/* Filled, flat-shaded triangles with a depth test: the mesh renderer's rasterizer (a scanline
 * rasterizer, as the paper's PocketPC renderer, on a z-buffer, target.h).
 *
 * Promise: mc_raster_triangle colours exactly the pixels whose centres lie inside the triangle and
 * whose depth there is strictly nearer than the target's, and writes nothing else. Coverage is
 * decided exactly, in integers (64-bit edge functions, no rounding); depth is the triangle's plane,
 * within 1 unit of its exact value, never outside the vertices' depths. No heap, no floating point,
 * no 64-bit division (a Cortex-M0 has none), bounded stack. Freestanding.
 *
 * Coordinates. x, y are target pixels in fixed point with MC_RASTER_SUBPIXEL_BITS fraction bits
 * (1/16 pixel); pixel (i, j) is the square [i, i+1) x [j, j+1), its centre (i + 1/2, j + 1/2); row 0
 * is the top row (y grows downward). z is a depth 0 .. MC_DEPTH_EMPTY - 2, smaller nearer; a larger
 * z is taken as MC_DEPTH_EMPTY - 2, so the target's promise holds whatever the caller passes.
 * Every |x|, |y| must be at most MC_RASTER_COORD_LIMIT (2^22: 262144 pixels either side of the
 * origin, room for any target plus a guard band): a triangle with a vertex beyond it draws nothing
 * and returns 0. The caller clips to that band (the rasterizer clips to the target itself, so
 * triangles partly or wholly off the target are fine inside it).
 *
 * Coverage (the top-left rule, as Direct3D). A pixel is covered when its centre is strictly inside
 * the triangle, or exactly on an edge that is a top edge (horizontal, the triangle below it) or a
 * left edge (not horizontal, the triangle to its right); a centre on a vertex is covered when both
 * edges through it allow it. So two triangles that share an edge cover each pixel centre on it
 * exactly once (no pixel written twice, no cracks), and a mesh that tiles a region covers each centre
 * inside it once. Coverage does not depend on the vertex order; zero-area triangles cover nothing.
 *
 * Culling. With MC_RASTER_CULL_BACK only front faces are drawn: counter-clockwise as the viewer sees
 * them with y up, i.e. (x1-x0)(y2-y0) - (x2-x0)(y1-y0) < 0 in target coordinates (y down). Without
 * it both orientations are drawn.
 *
 * Depth. At a covered centre p the exact depth is the plane through the three (x, y, z), zp. The
 * rasterizer evaluates that plane in fixed point with MC_RASTER_DEPTH_FRAC_BITS fraction bits
 * (gradients and the value at the triangle's first covered pixel rounded to nearest, then stepped
 * exactly), a value zf with |zf - zp| < 1/4, and writes clamp(floor(zf + 1/2), zmin, zmax) with
 * zmin, zmax the smallest and largest vertex z. The written depth is therefore within 3/4 of zp, and
 * is zp rounded half up wherever zp is more than 1/4 away from a half-integer. It is written, with
 * the colour, only where it is strictly less than the depth already there: an equal depth keeps the
 * pixel.
 */
#ifndef MODELC_RASTER_H
#define MODELC_RASTER_H

#include <stdint.h>
#include "config.h"   /* MC_MESH_SELECT */
#include "sdepth.h"
#include "target.h"

#define MC_RASTER_SUBPIXEL_BITS 4
#define MC_RASTER_COORD_LIMIT ((int32_t)1 << 22)
#define MC_RASTER_DEPTH_FRAC_BITS 18

/* flags */
#define MC_RASTER_CULL_BACK 1u

typedef struct mc_raster_vertex {
    int32_t x, y;   /* 1/16 pixel */
    uint32_t z;     /* 0 .. MC_DEPTH_EMPTY - 2 */
} mc_raster_vertex;

/* floor(v / 16) for |v| < 2^26: an arithmetic shift (config.h MC_ASR_CHECK) */
MC_ALWAYS_INLINE int32_t mc_raster_floor16(int32_t v) { return v >> 4; }

/* Pixels i0 .. i1 across, j0 .. j1 down: the pixels whose centres a triangle may cover. */
typedef struct mc_raster_box {
    int32_t i0, i1, j0, j1;
} mc_raster_box;

/* The least and the greatest of three coordinates: by selects with MC_MESH_SELECT (which corner is
 * the least is a coin toss to a predictor), else by branches (fewer instructions where a branch
 * costs a cycle or two); config.h. */
MC_ALWAYS_INLINE int32_t mc_raster_min3(int32_t c0, int32_t c1, int32_t c2)
{
#if MC_MESH_SELECT
    const int32_t a = c0 < c1 ? c0 : c1;
    return a < c2 ? a : c2;
#else
    return c0 < c1 ? (c0 < c2 ? c0 : c2) : (c1 < c2 ? c1 : c2);
#endif
}
MC_ALWAYS_INLINE int32_t mc_raster_max3(int32_t c0, int32_t c1, int32_t c2)
{
#if MC_MESH_SELECT
    const int32_t a = c0 > c1 ? c0 : c1;
    return a > c2 ? a : c2;
#else
    return c0 > c1 ? (c0 > c2 ? c0 : c2) : (c1 > c2 ? c1 : c2);
#endif
}

/* The box of the pixels of a width x height frame whose centres triangle v may cover (every pixel it
 * covers lies in it); 0 when there is none, or when a corner lies beyond MC_RASTER_COORD_LIMIT (the
 * triangle then draws nothing). The rasterizer's own first test, so that a pass over many faces can
 * reject most of them inline. The centres (16 i + 8, 16 j + 8) that can be covered lie in the
 * corners' bounding box, and not on its right or bottom side: a centre there lies on a vertical
 * right edge or a horizontal bottom edge, or on the rightmost or lowest corner, which has a right
 * edge through it. So xmin <= 16 i + 8 < xmax and ymin <= 16 j + 8 < ymax, on the frame.
 * mc_raster_centre_run gives one axis's run of pixels (lo .. hi of side; 0 when empty),
 * mc_raster_centre_run_of the same from the least and the greatest coordinate. */
MC_ALWAYS_INLINE int mc_raster_centre_run_of(int32_t cmin, int32_t cmax, uint32_t side, int32_t *lo, int32_t *hi)
{
    int32_t a = mc_raster_floor16(cmin + 7), b = mc_raster_floor16(cmax - 9);
    if (a < 0) a = 0;
    if (b > (int32_t)side - 1) b = (int32_t)side - 1;
    *lo = a, *hi = b;
    return a <= b;   /* also 0 on an empty frame */
}
MC_ALWAYS_INLINE int mc_raster_centre_run(int32_t c0, int32_t c1, int32_t c2, uint32_t side, int32_t *lo, int32_t *hi)
{
    const int32_t cmin = mc_raster_min3(c0, c1, c2), cmax = mc_raster_max3(c0, c1, c2);
    if (cmin < -MC_RASTER_COORD_LIMIT || cmax > MC_RASTER_COORD_LIMIT) return 0;
    return mc_raster_centre_run_of(cmin, cmax, side, lo, hi);
}
/* mc_raster_centre_run of coordinates known to lie within the limit (a projected vertex without a
 * flag: xform.h's band), without testing it. */
MC_ALWAYS_INLINE int mc_raster_centre_run_inside(int32_t c0, int32_t c1, int32_t c2, uint32_t side, int32_t *lo, int32_t *hi)
{
    return mc_raster_centre_run_of(mc_raster_min3(c0, c1, c2), mc_raster_max3(c0, c1, c2), side, lo, hi);
}

MC_ALWAYS_INLINE int mc_raster_centres(const mc_raster_vertex v[3], uint32_t width, uint32_t height, mc_raster_box *b)
{
    /* rows first: most faces of a dense mesh have no centre between their rows */
    return mc_raster_centre_run(v[0].y, v[1].y, v[2].y, height, &b->j0, &b->j1) &&
           mc_raster_centre_run(v[0].x, v[1].x, v[2].x, width, &b->i0, &b->i1);
}

/* Draws v[0], v[1], v[2] in `color` with the depth test and returns the number of target pixels the
 * triangle covers (before the depth test; 0 when culled, degenerate or out of range). */
uint32_t mc_raster_triangle(const mc_target *t, const mc_raster_vertex v[3], uint8_t color, unsigned flags);

/* The face pass of hidden-line removal over a sparse depth buffer (sdepth.h): empties every pixel in
 * use that mc_raster_triangle would cover, with the same flags, at a depth there not greater than
 * the pixel's entry (the entry survives only where it is strictly nearer than the triangle, as a
 * line drawn after the faces with mc_line's depth test). Visits only pixels in use: a triangle whose
 * box holds none costs its box. Returns the pixels emptied. */
uint32_t mc_raster_triangle_hide(mc_sdepth *s, const mc_raster_vertex v[3], unsigned flags);

/* mc_raster_triangle_hide with the face pushed back by offset depth units (OpenGL's polygon offset):
 * an entry of depth e is emptied where the triangle's depth there is at most e - offset (an entry
 * nearer than offset is never emptied). For edges that lie on the faces that hide others. */
uint32_t mc_raster_triangle_hide_offset(mc_sdepth *s, const mc_raster_vertex v[3], unsigned flags, uint32_t offset);

/* mc_raster_triangle_hide of a triangle whose box the caller has taken: *box as mc_raster_centres
 * sets it for s's frame, where it returned 1 (the same pixels emptied; a pass over many faces that
 * rejects most by their box need not have it taken twice). */
uint32_t mc_raster_triangle_hide_box(mc_sdepth *s, const mc_raster_vertex v[3], unsigned flags, const mc_raster_box *box);

/* The least depth the triangle with corner depths z0, z1, z2 has at any pixel it covers (each z taken
 * as at most MC_DEPTH_EMPTY - 2, as the rasterizer takes it): a face pass empties an entry of depth e
 * only where this, pushed back by the offset, is at most e. */
MC_ALWAYS_INLINE uint32_t mc_raster_least_depth(uint32_t z0, uint32_t z1, uint32_t z2)
{
    const uint32_t z01 = z0 < z1 ? z0 : z1, z = z2 < z01 ? z2 : z01;
    return z < MC_DEPTH_EMPTY - 2u ? z : MC_DEPTH_EMPTY - 2u;
}

/* One pixel's worth of the triangle's steepest depth slope: floor(max(|dz/dx|, |dz/dy|)) + 1 depth
 * units per pixel (so at least 1), or 0 for a triangle of no area, which covers no pixel. */
uint64_t mc_raster_slope(const mc_raster_vertex v[3]);

#endif
