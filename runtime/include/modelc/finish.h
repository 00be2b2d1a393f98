/* 2D finishing: closes holes the one-pixel-per-leaf renderer leaves when a view is rotated or zoomed.
 *
 * Two fills, selected by mc_fill (mc_finish) or called directly:
 *
 * MC_FILL_PIXEL, mc_finish_pixel_holes: fills every empty pixel whose four neighbours (left, right,
 * up, down) are all drawn, with the colour and depth of the nearest of them. A filled pixel's right
 * and lower neighbours were drawn before the pass, so a fill never enables another: exactly the
 * one-pixel holes of the input are closed, in one pass, with no scratch memory. Border pixels are
 * never filled.
 *
 * MC_FILL_SCANLINE, mc_finish_scanline_holes: the source paper's scanline neighbourhood criterion
 * (Barth, Schwanecke & Wild, section 4: "closes holes of type 1-4; elimination of potential holes at
 * the border (type 5) is not attempted"). From an empty pixel it looks along four lines, the row, the
 * column and the two diagonals, up to MC_FILL_REACH pixels each way (config.h, default 3) for a drawn
 * pixel. A line is bounded when it meets a drawn pixel on both sides. The pixel is filled when at
 * least three of its four lines are bounded, with the colour of the nearest (smallest depth) of the
 * drawn pixels met, and the depth MC_DEPTH_FILLED: behind every drawn pixel (a later render on
 * top draws over it) but not empty. Only pixels drawn by the renderer count as bounds, never filled
 * ones, so the result does not depend on the scan order, a fill never enables another, and a
 * second call fills nothing more. The hole types (the paper's figure is not in its text, so they are defined here by shape):
 *   1: one empty pixel with its four neighbours drawn (what MC_FILL_PIXEL closes too);
 *   2: horizontal gaps: a row of empty pixels one pixel high, 2..MC_FILL_REACH long, or a crack of
 *      any length along a row (its column and both diagonals are bounded);
 *   3: vertical gaps: the same along a column;
 *   4: diagonal cracks, and small clusters (2x2 blocks, L shapes, pairs touching at a corner) up to
 *      MC_FILL_REACH pixels across;
 *   5: border holes: empty pixels on the outline of the drawn region, open to the background along
 *      two or more of the four lines: the outside of straight and slanted (staircase) edges, notches
 *      one pixel deep, concave corners. These are left open, so the outline of the model is neither
 *      grown nor smoothed (for a digitally convex region no outside pixel has even one bounded line).
 * One pass over the target, no scratch memory.
 *
 * Both return the number of pixels filled.
 */
#ifndef MODELC_FINISH_H
#define MODELC_FINISH_H

#include <stdint.h>
#include "target.h"

/* Depth of a pixel the scanline fill closed: renderers never write it (target.h). */
#define MC_DEPTH_FILLED (MC_DEPTH_EMPTY - 1u)

typedef enum mc_fill {
    MC_FILL_NONE = 0,       /* leave holes open */
    MC_FILL_PIXEL = 1,      /* one-pixel holes (four-neighbour criterion) */
    MC_FILL_SCANLINE = 2,   /* the paper's scanline neighbourhood criterion, hole types 1-4 */
    MC_FILL_DEFAULT = 3     /* MC_FILL_DEFAULT_MODE from config.h (any other value means this too) */
} mc_fill;

uint32_t mc_finish_pixel_holes(const mc_target *t);
uint32_t mc_finish_scanline_holes(const mc_target *t);

/* The fill `mode` selects; returns the number of pixels filled. */
uint32_t mc_finish(const mc_target *t, mc_fill mode);

#endif
