/* Screen positions of the renderer (render.c): the one place that knows their number type.
 *
 * The renderer moves points by adding displacement vectors and reads a pixel off each position.
 * By default (MC_FLOAT 0) a position is Q MC_FRAC_BITS fixed point in an int32, and the hot loop
 * packs x and y into one int64 (x * 2^32 + y: on screen both are non-negative, so one 64-bit
 * addition moves a point in both axes). With MC_FLOAT 1 (config.h) positions are single-precision
 * floats in pixels and x, y a pair: the same walk, culling, depth test and footprints, built only so
 * that make bench-accuracy can set fixed point against float. Viewers and firmware never use it.
 *
 * Depths go through the same type: orthographic depths are kept in depth-buffer units and stored as
 * they are (a conversion to uint16_t, which truncates a float as it does nothing to an integer).
 */
#ifndef MODELC_POS_H
#define MODELC_POS_H

#include <stdint.h>
#include "modelc/config.h"

#define F MC_FRAC_BITS

#if MC_FLOAT

typedef float mc_pos;                      /* pixels */
typedef float mc_pos_wide;                 /* products and distances: the same float */
typedef struct mc_pos2 { float x, y; } mc_pos2;

#define POS2(x, y) ((mc_pos2){(x), (y)})
#define POS2_ADD(a, b) ((mc_pos2){(a).x + (b).x, (a).y + (b).y})
#define POS2_X(p) ((p).x)
#define POS2_Y(p) ((p).y)
/* pixel column / row of a position known to be on screen (non-negative: truncation is the floor) */
#define POS2_COL(p) ((intptr_t)(p).x)
#define POS2_ROW(p) ((intptr_t)(p).y)
/* n pixels, and n half pixels, as a position */
#define POS_PIXELS(n) ((float)(n))
#define POS_HALF_PIXELS(n) ((float)(n) * 0.5f)

/* The pixel a position falls in, rounded toward minus infinity. Positions stay within
 * MC_COORD_LIMIT (views are clamped, view.h), so the conversion is always defined. */
static inline int32_t pos_floor(mc_pos v)
{
    int32_t i = (int32_t)v;
    return i - (v < (float)i);
}

#else

typedef int32_t mc_pos;                    /* Q F pixels */
typedef int64_t mc_pos_wide;               /* Q F pixels, with room for products */
typedef int64_t mc_pos2;                   /* x * 2^32 + y, each Q F */

#define POS2(x, y) ((int64_t)(x) * 4294967296 + (y))
#define POS2_ADD(a, b) ((a) + (b))
#define POS2_X(p) ((int32_t)((p) >> 32))
#define POS2_Y(p) ((int32_t)(uint32_t)(p))
#define POS2_COL(p) ((intptr_t)((p) >> (32 + F)))
#define POS2_ROW(p) ((intptr_t)((uint32_t)(p) >> F))
#define POS_PIXELS(n) ((int32_t)(n) << F)
#define POS_HALF_PIXELS(n) ((int32_t)(n) << (F - 1))

static inline int32_t pos_floor(mc_pos v) { return v >> F; }

#endif

#endif
