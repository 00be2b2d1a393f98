/* Image edges for edge-based tracking: the pixels of an 8-bit grey frame that lie on an intensity
 * edge, each with the orientation of its edge, in integers (Kissling et al.'s tracker matches the
 * pixels of a model's projected edges against these, track.h).
 *
 * Promise (mc_imgedge). For each pixel (x, y) with 1 <= x <= w - 2 and 1 <= y <= h - 2, I its
 * grey level:
 *   gradient   the Sobel operator, y down:
 *                gx = I(x+1, y-1) + 2 I(x+1, y) + I(x+1, y+1) - I(x-1, y-1) - 2 I(x-1, y) - I(x-1, y+1)
 *                gy = I(x-1, y+1) + 2 I(x, y+1) + I(x+1, y+1) - I(x-1, y-1) - 2 I(x, y-1) - I(x+1, y-1)
 *              exact (|gx|, |gy| <= 1020), and its squared magnitude m = gx^2 + gy^2, exact;
 *              m is 0 on the frame's border pixels, which have no gradient;
 *   candidate  m >= threshold^2 (threshold in the gradient's units, 1 .. 1442; a step of d grey
 *              levels across a straight edge gives a magnitude of 4 d);
 *   orientation the angle of (gx, gy) modulo 180 degrees (an edge looks the same from both sides:
 *              the object may be darker or lighter than what lies behind it), in MC_IMGEDGE_DIRS
 *              bins of 22.5 degrees centred on 0, 22.5, ... 157.5 (bin 0: a horizontal gradient, so a
 *              vertical edge; bin 4: a horizontal edge; angles grow from +x towards +y, y down);
 *   thinning   non-maximum suppression across the edge: the gradient's orientation quantized to
 *              0, 45, 90 or 135 degrees (sectors of 45 degrees centred on those, modulo 180) gives
 *              the neighbours n+ at +x, +x+y, +y or -x+y of the pixel and n- opposite it; a candidate
 *              is an edge pixel when m > m(n-) and m >= m(n+) (so of two equal pixels across an edge
 *              one stays);
 *   output     out[y * w + x] = 1 + bin for an edge pixel, else 0 (border pixels: 0).
 * Bins and sectors are decided by comparing |gy| 2^16 with gx times the boundaries' tangents rounded
 * to Q16, in 64-bit integers: the bin of the exact angle, except for a gradient within 2^-16 rad of a
 * boundary (the constants' rounding), where it may be the neighbouring one. Returns the number of edge
 * pixels.
 *
 * Memory: the caller's: out (w * h bytes, written in full, also holding the work of the row before
 * the one being read) and scratch, MC_IMGEDGE_SCRATCH_WORDS(w) words (three rows of m). The frame is
 * read row by row, once; work is proportional to w * h. No heap, no floating point, no division.
 * Freestanding.
 */
#ifndef MODELC_IMGEDGE_H
#define MODELC_IMGEDGE_H

#include <stdint.h>

#define MC_IMGEDGE_DIRS 8
#define MC_IMGEDGE_THRESHOLD_MAX 1442   /* above the largest magnitude, sqrt(2) 1020 */
#define MC_IMGEDGE_SCRATCH_WORDS(w) (3u * (uint32_t)(w))

/* The edge pixels of grey frame img (w x h, rows stride bytes apart) into out, as promised above.
 * Frames narrower or lower than 3 pixels have none. threshold is clamped to 1 .. THRESHOLD_MAX. */
uint32_t mc_imgedge(const uint8_t *img, uint32_t stride, uint16_t w, uint16_t h, uint16_t threshold, uint8_t *out,
                    uint32_t *scratch);

/* The orientation bin (0 .. MC_IMGEDGE_DIRS - 1) of a direction (gx, gy), not (0, 0), any int32
 * components except INT32_MIN, y down: mc_imgedge's bins, by the same Q16 tangents. A tracker takes
 * a model line's own bin from its normal on the screen. */
unsigned mc_imgedge_bin(int32_t gx, int32_t gy);

/* Whether two orientation bins (0 .. MC_IMGEDGE_DIRS - 1) lie within tolerance bins of each other,
 * around the half circle (bins 0 and 7 are neighbours). */
static inline int mc_imgedge_dirs_match(unsigned a, unsigned b, unsigned tolerance)
{
    const unsigned d = (a - b) & (MC_IMGEDGE_DIRS - 1u);
    return d <= tolerance || MC_IMGEDGE_DIRS - d <= tolerance;
}

/* The bins within tolerance of bin, as a mask (bit b for bin b): what a line of that bin matches. */
static inline uint8_t mc_imgedge_bin_mask(unsigned bin, unsigned tolerance)
{
    unsigned m = 0;
    for (unsigned b = 0; b < MC_IMGEDGE_DIRS; b++) m |= (unsigned)mc_imgedge_dirs_match(b, bin, tolerance) << b;
    return (uint8_t)m;
}

/* Bytes of scratch mc_imgedge_masks needs. */
#define MC_IMGEDGE_MASK_SCRATCH(w, radius) (((uint32_t)(radius) + 1u) * (uint32_t)(w))

/* Turns mc_imgedge's codes into masks, in place: pixel p's mask has bit b set when an edge pixel of
 * bin b lies within radius pixels of p along both axes (a square of side 2 radius + 1, cut by the
 * frame), so that a tracker's line pixel matches an image edge up to radius pixels away. Two passes
 * of bitwise ORs (across, then down) with MC_IMGEDGE_MASK_SCRATCH bytes of scratch; work about
 * 2 w h (2 radius + 1). radius 0 only turns codes into masks. */
void mc_imgedge_masks(uint8_t *edges, uint16_t w, uint16_t h, unsigned radius, uint8_t *scratch);

/* The second half of mc_imgedge_masks on masks: each pixel's mask ORed over the square of radius
 * around it, in place (MC_IMGEDGE_MASK_SCRATCH bytes of scratch). Squares add up: masks spread by r1
 * and then by r2 are the codes' masks spread by r1 + r2, so a tracker that wants both a fine and a
 * coarse radius spreads its fine masks on. radius 0 leaves them as they are. */
void mc_imgedge_spread(uint8_t *masks, uint16_t w, uint16_t h, unsigned radius, uint8_t *scratch);

#endif
