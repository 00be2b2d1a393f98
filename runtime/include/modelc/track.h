/* Edge-based tracking (Kissling, Mitchell, Oskam and Gross, after Klein and Murray): the score of a
 * camera pose. The model's lines are drawn first into a sparse depth buffer (sdepth.h), each pixel
 * matched against the camera frame's edges (imgedge.h); then its faces empty the line pixels they
 * hide (raster.h's face pass, which visits only pixels in use); what is left are the visible line
 * pixels, and those of them that matched.
 *
 * Promise (mc_track_score), for a pose: every vertex projected (camera.h); then each line, in order:
 *   - a line with an end beyond the band (MC_XFORM_FAR_OUT, 2^17 pixels off the image) is left out;
 *     one with an end nearer than the camera's near plane is cut there (mc_camera_clip_segment),
 *     and left out when nothing is left;
 *   - its orientation bin is mc_imgedge_bin of its normal on the screen (from its ends in 1/16
 *     pixel); a line whose ends land on the same 1/16-pixel point has none and is left out;
 *   - its pixels (line.h: the Bresenham line between the pixels holding its ends, with their depths)
 *     go into the buffer with mc_track_line, colour 1 + bin, matched where the frame's mask
 *     has a bin within the view's tolerance of that bin (an image edge of such an orientation within
 *     the masks' radius); of several entries at a pixel the nearest stays;
 * then each face: left out with a corner beyond the band; cut at the near plane where it must be
 * (mc_camera_clip_triangle, then a fan); each triangle culled when seen from behind if the model is
 * closed, else drawn both ways, pushed back by its one-pixel depth slope plus 2 (mc_raster_slope:
 * the polygon offset that keeps a line lying on a face visible), and emptying the entries it hides
 * (mc_raster_triangle_hide_offset). visible and matched are then the entries left and those of them
 * matched: the counts a dense z-buffer would give with the same rules (tests/unit/test_track.c holds
 * them to one).
 *
 * Convex models (edges.h convex) with every vertex beyond the near plane and inside the band take a
 * shortcut: no face pass; each line goes into the buffer when one of its two faces is seen from
 * outside (the face pass's own sign rule) and is left out whole otherwise; pixels and lines then
 * count only the lines drawn. visible and matched are those of the dense z-buffer but where a
 * hidden line meets the silhouette, whose last pixels the faces' fill rule may leave uncovered
 * (tests/unit/test_track.c: at most 12 pixels off on the cube, most poses exact).
 *
 * Work: the vertices, the lines' pixels, and for each face its corners and box (a face whose box
 * holds no pixel in use costs nothing more; no face at all in a convex model's shortcut); the buffer
 * is emptied at the start by its bits alone (mc_sdepth_forget: the depths and colours of pixels not
 * in use are left stale, and nothing here reads them). Memory: the caller's (the view's buffer, frame
 * edges and vertex cache); no heap, no floating point, bounded stack. Deterministic. Freestanding.
 */
#ifndef MODELC_TRACK_H
#define MODELC_TRACK_H

#include <stdint.h>
#include "camera.h"
#include "edges.h"
#include "line.h"
#include "sdepth.h"

/* What scoring a pose draws with. */
typedef struct mc_track_view {
    const mc_edges *model;
    const mc_camera *cam;
    mc_sdepth *sd;              /* cam's width x height, keeping matched bits (sdepth.h) */
    const uint8_t *masks;       /* the frame's edge masks (imgedge.h mc_imgedge_masks), width x height */
    mc_xvertex *cache;          /* model->vertices entries: the projected vertices */
    uint8_t tolerance;          /* orientation bins a match may be off by */
    const uint8_t *fine;        /* the same frame's masks spread by a smaller radius, which the particle
                                   filter's later layers score with (particles.h), or NULL: masks */
} mc_track_view;

typedef struct mc_track_score {
    uint32_t visible;           /* line pixels no face hides */
    uint32_t matched;           /* of those, the ones on a frame edge of a matching orientation */
    uint32_t pixels;            /* line pixels drawn on the frame, before hiding */
    uint32_t lines;             /* lines drawn */
} mc_track_score;

/* The tracker's line pass: line.h's mc_line_sdepth into a buffer that keeps matched bits (nothing,
 * 0, otherwise), each pixel's entry matched when masks (imgedge.h mc_imgedge_masks, for the same
 * frame) has a bit of want set there: an image edge near it of an orientation the line accepts
 * (want: mc_imgedge_bin_mask of the line's own bin and a tolerance). Returns the line's pixels on
 * the frame. */
uint32_t mc_track_line(mc_sdepth *s, mc_line_vertex a, mc_line_vertex b, uint8_t color, uint16_t depth_offset,
                       const uint8_t *masks, uint8_t want);

/* Scores pose through view (see the promise). Returns MC_OK, or MC_ERR_ARG (a null argument, a
 * buffer without matched bits or of another size than the camera's image). */
int mc_track_score_pose(const mc_track_view *view, const mc_pose *pose, mc_track_score *score);

#endif
