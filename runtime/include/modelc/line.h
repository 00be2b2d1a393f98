/* Lines on a target: the silhouettes, creases and borders of a mesh line drawing, drawn after its
 * faces and hidden by their depths (z-buffer hidden-line removal with a depth offset), or offered to
 * a sparse depth buffer before the faces (sdepth.h).
 *
 * Promise (pixels): mc_line draws exactly the pixels of the unclipped Bresenham line between its
 * endpoints that lie on the target, both endpoints included, and returns how many there are (before
 * the depth test). The line is walked from its start, the endpoint with the smaller coordinate on
 * the major axis (x when |dx| >= |dy|, else y), so a->b and b->a are the same line, pixels and
 * depths. With D = |major delta| and M = |minor delta|, step i = 0..D is the pixel whose major
 * coordinate is the start's plus i and whose minor coordinate moves from the start's, towards the
 * other endpoint, by the integer nearest to i * M / D, halves rounded towards the start (the
 * midpoint rule: the minor coordinate steps when the line passes strictly beyond the midpoint).
 *
 * Clipping: Cohen-Sutherland outcodes reject a line wholly beyond one side of the target and find
 * the sides it crosses; the steps on the target are a single run (both coordinates are monotonic in
 * the step), whose ends are computed exactly in integers, and the walk starts at the run's first
 * step with that step's own error term. So a clipped line is the unclipped line cut, never a line
 * re-rounded between clip points, and the work is the run's pixels plus a constant (no work at all
 * for the part off the target). Coordinates are accepted up to |x|, |y| <= MC_LINE_COORD_MAX
 * (2^24); a line with an endpoint beyond draws nothing and returns 0.
 *
 * Depth: the depth of step i is the integer nearest to za + (zb - za) * i / D (a, b as walked:
 * from the start), halves rounded towards the start's depth, so always within 1/2 unit of the exact
 * value, and a clipped line keeps the unclipped line's depths. Endpoint depths above
 * MC_LINE_DEPTH_MAX (MC_DEPTH_EMPTY - 2) are taken as MC_LINE_DEPTH_MAX, so a line never writes a
 * depth at or above MC_DEPTH_EMPTY - 1 (target.h). A line that is one pixel has the nearer depth.
 *
 * Depth test (mc_line_style; a null style means offset 0, tested, colour only): a pixel of depth z
 * is drawn where max(z - depth_offset, 0) < the target's depth there, strictly, so a line lying on
 * a face drawn at the same depths shows through it by the offset; with MC_LINE_NO_DEPTH_TEST it is
 * drawn everywhere. A drawn pixel gets the colour, and its depth too with MC_LINE_WRITE_DEPTH
 * (without it lines never hide each other, whatever order they are drawn in).
 *
 * Integer arithmetic only, no division wider than 32 bits (the exact clip entry divides 64-bit
 * products by shift and subtract), bounded stack, no recursion. Freestanding.
 */
#ifndef MODELC_LINE_H
#define MODELC_LINE_H

#include <stdint.h>
#include "sdepth.h"
#include "target.h"

/* Largest |x|, |y| of an endpoint. */
#define MC_LINE_COORD_MAX ((int32_t)1 << 24)
/* Largest depth a line draws with. */
#define MC_LINE_DEPTH_MAX (MC_DEPTH_EMPTY - 2u)

/* An endpoint: pixel (x, y), row 0 at the top; z its depth, 0 .. MC_LINE_DEPTH_MAX. */
typedef struct mc_line_vertex {
    int32_t x, y;
    uint32_t z;
} mc_line_vertex;

/* mc_line_style.flags */
#define MC_LINE_NO_DEPTH_TEST 1u   /* draw every pixel of the line on the target */
#define MC_LINE_WRITE_DEPTH 2u     /* drawn pixels take the line's depth as well as its colour */

typedef struct mc_line_style {
    uint16_t depth_offset;   /* subtracted from the line's depth before the test, saturating at 0 */
    uint8_t flags;           /* MC_LINE_* */
} mc_line_style;

/* Draws the line from a to b in palette index color; returns its pixels on the target (drawn or
 * hidden). s may be null. */
uint32_t mc_line(const mc_target *t, mc_line_vertex a, mc_line_vertex b, uint8_t color, const mc_line_style *s);

/* The same line's pixels on the frame of a sparse depth buffer (sdepth.h), each offered to it
 * (mc_sdepth_insert) with colour color and its depth less depth_offset, saturating at 0: the
 * depth the face pass (raster.h mc_raster_triangle_hide) tests, as mc_line tests against faces
 * drawn first. Returns the line's pixels on the frame. */
uint32_t mc_line_sdepth(mc_sdepth *s, mc_line_vertex a, mc_line_vertex b, uint8_t color, uint16_t depth_offset);


#endif
