/* Hidden lines by quantitative invisibility (Appel): the silhouettes, creases and borders of the
 * current level of detail (mesh_lines.h: the same edges, kinds, facing bits and colours), each drawn
 * exactly where no face of the level lies in front of it, decided in integers on the projected
 * corners, with no z-buffer and no faces drawn.
 *
 * Geometry. Every corner is projected by mc_xform_vertex (x, y in 1/16 pixel, z a 16-bit depth,
 * xform.h). A face is the triangle of its three projected corners in (x, y, z): its depth is affine
 * over its projected triangle for both projections (xform.h: the perspective depth is affine in
 * 1/distance, which is affine across the image of a plane). A face with a corner flagged
 * MC_XFORM_NEAR or MC_XFORM_FAR_OUT hides nothing (counted in stats.skipped_faces: it has no
 * projected triangle to test against), nor does a face of zero projected area; its facing bit is
 * still mc_mesh_facing's (its plane's, mesh_lines.h), so kinds are mc_mesh_lines'. A line is an edge
 * of a kind chosen by flags, taken as mc_mesh_lines takes it: from corner k to corner k+1 of its
 * first face f (half-edge h = MC_HALF_EDGE(f, k)), A and B its ends as mc_mesh_edge_ends gives them:
 * the projected corners, or, when one is flagged, the ends of the segment clipped against the near
 * plane and the guard band (xform.h; counted in stats.clipped, or in stats.clipped_away when nothing
 * is left, and then not drawn). On it, P(t) = A + t (B - A) and z(t) = zA + t (zB - zA), 0 <= t <= 1,
 * in the same integer coordinates (the depth along a projected segment is affine too).
 *
 * Covers in front. A face F covers the line at t on side S (S = L or R: left or right of B - A on
 * the screen) when
 *   - F is not one of the line's own faces (the one or two faces on its edge never hide it);
 *   - the points P(t) + e n_S lie strictly inside F's projected triangle for every small enough
 *     e > 0, n_S the screen normal of B - A towards S (so a line running exactly along an edge of F
 *     is inside F on F's side only, and a point on F's outline is not inside on the other side);
 *   - F's plane at P(t) is strictly nearer than z(t) (an equal depth is not in front: a face
 *     through the line's point, or holding the line in its plane, does not hide it).
 * QI_S(t) is the number of faces covering at t on side S. Away from finitely many t (where the line
 * passes a projected edge or corner of a face, or through a face) both counts are locally constant;
 * there the line is visible when QI_L = 0 or QI_R = 0 (hidden only where faces in front cover both
 * sides of it). The visible set V is the closure of those visible t in [0, 1]: closed pieces [a, b]
 * with a < b. So a point where visibility changes belongs to the visible piece; a line that touches
 * the outline of a surface in front, passes behind one of its outline corners or runs along its
 * outline stays visible there; a line behind an edge between two faces in front is hidden; at t = 0
 * and t = 1 only the limits from inside the segment count.
 *
 * Pixels. A line's pixels are exactly mc_line's (line.h: the Bresenham line between the pixels
 * holding A and B, clipped to the target, walked from mc_line's start) with mc_line's depths. Step
 * i (0 .. D) of the walk stands for t = i/D measured from that start (from A, or from B when
 * mc_line starts at B); a one-pixel line (D = 0) stands for both t = 0 and t = 1. A pixel is drawn
 * (colour MC_LINES_*_COLOR and the line's depth written, no depth test) exactly when its t is in V;
 * nothing else is written. The visible pieces are thus cut out of the one Bresenham line, never
 * re-rounded. The faces need not be drawn first (for a lines-only drawing clear the target, draw,
 * then fill what is still empty with paper, as mesh_frame.c does). Lines are drawn in mc_mesh_lines'
 * order, so with MC_LINES_NO_HIDING the target is mc_mesh_lines' with MC_LINES_NO_HIDING, byte for
 * byte.
 *
 * Algorithm (Appel's). QI changes along a line only where the line passes behind a contour: an edge
 * whose faces (those that can hide) do not lie one on each side of it on the screen: a silhouette
 * (a front and a back face), a border, an edge beside a face that hides nothing. There QI_S changes
 * by the contour's faces on the far side minus those on the near side. Per frame:
 *   1. the faces once: facing bits (mc_mesh_facing's) and the bits of the faces that can hide;
 *   2. the edges once: kinds (mc_mesh_edge_kind), the contours (projected corners, faces on each
 *      side) and the lines with a pixel on the target (ends clipped where one is flagged);
 *   3. two screen grids: the contours by bounding box (cells of 8 pixels or more, at most about two
 *      cells per contour) and the lines' ends (cells of 2 pixels or more, at most about sixteen per
 *      line), made coarser until they fit in the work buffer;
 *   4. the faces once more, each tested only against the line ends in the cells under its bounding
 *      box: the ray tests giving QI_L and QI_R at t -> 0+ and t -> 1- exactly;
 *   5. per line, the contours in the cells it passes (each tested once): where one crosses the line
 *      at 0 < t < 1 strictly in front, QI_S changes (on one side only where the contour touches the
 *      line at a corner of its own, on neither where it runs along the line). The changes, sorted,
 *      give the visibility changes as exact fractions t = num / den.
 * A line is instead computed face by face, from the definition above (each face's interval of
 * covering on each side; work: the level's faces), when QI(0+) plus its changes is not QI(1-) (the
 * line passes through a face in depth: Appel's method assumes surfaces never do, but rounding can make
 * nearly touching parts of a level meet), when a contour meets it at equal depth, or when it crosses
 * more contours than the work buffer holds events for; stats.exact_lines counts these. Two passes
 * through faces between the ends that cancel (a line dipping behind a face and out again through
 * faces, with no contour in front to show it) are the one case left wrong: the ends agree.
 * All of it is integer: 64-bit products (every value is bounded: |x|, |y| <= 2^21 in the band), sums
 * checked below 2^63, fractions compared through 128-bit products made of 32-bit halves; no division
 * wider than 32 bits (the projection's and the clipper's are xform_vertex.c's), no floating point, no
 * recursion, no memory function calls. Stack: about 1200 bytes on a Cortex-M4 (gcc -O2, the
 * deepest paths through mc_mesh_edge_kind and mc_mesh_edge_ends), not counting the hook.
 * Freestanding.
 *
 * Work: the faces twice (their corners projected, or read from the vertex cache; a face with a
 * flagged corner also its plane test, a line with a flagged end its clipping); the edges once; per
 * line the contours in its cells and, for the ray tests, the faces whose bounding-box cells hold its
 * ends; per line pixel one comparison of fractions. Memory: the caller's, with no heap:
 *   facing  MC_MESH_FACING_BYTES(pm->faces) (mesh_lines.h), set to the frame's facing bits;
 *   cache   null, or MC_QI_CACHE_BYTES(pm->vertices) (mc_xvertex aligned): each present vertex is
 *           then projected once per frame instead of once per use;
 *   work    work_bytes (any alignment) holding the frame's records: at least
 *           MC_QI_WORK_BYTES(faces, lines, contours, side) for the level's faces, the frame's lines
 *           and contours and the target's longer side; more makes the grids finer (faster). With
 *           fewer, nothing is drawn, MC_ERR_SIZE is returned and stats.work_needed is that figure
 *           for the frame (a lower bound when not even the per-face and per-step arrays fit).
 */
#ifndef MODELC_MESH_QI_H
#define MODELC_MESH_QI_H

#include <stdint.h>
#include "mesh_lines.h"

/* flags, with mesh_lines.h's MC_EDGE_* kinds and MC_LINES_NO_HIDING */
#define MC_QI_FACE_BY_FACE 16u   /* every line from the definition, face by face (tests, measurement) */

/* Bytes per record in the work buffer. */
#define MC_QI_LINE_RECORD 48u
#define MC_QI_CONTOUR_RECORD 28u
#define MC_QI_EVENT_RECORD 18u
#define MC_QI_MIN_EVENTS 16u

/* The least work buffer for a level of `faces` faces, `lines` lines and `contours` contours on a
 * target whose longer side is `side` pixels (the grids are then one cell each). */
#define MC_QI_WORK_BYTES(faces, lines, contours, side)                                                              \
    (64u + ((uint32_t)(faces) + 7u) / 8u + ((uint32_t)(side) + 8u) / 8u + 16u * ((uint32_t)(side) + 2u) +           \
     (uint32_t)(lines) * (MC_QI_LINE_RECORD + 40u) + (uint32_t)(contours) * (MC_QI_CONTOUR_RECORD + 4u) + 16u +    \
     MC_QI_MIN_EVENTS * MC_QI_EVENT_RECORD)

/* Bytes of vertex cache for a part of `vertices` vertices (pmesh.h V). */
#define MC_QI_CACHE_BYTES(vertices) ((uint32_t)(vertices) * (uint32_t)sizeof(mc_xvertex))

typedef struct mc_qi_buffers {
    uint8_t *facing;       /* MC_MESH_FACING_BYTES(pm->faces) */
    mc_xvertex *cache;     /* null or MC_QI_CACHE_BYTES(pm->vertices) */
    void *work;            /* work_bytes */
    uint32_t work_bytes;
} mc_qi_buffers;

/* A parameter along a line: t = num / den, den > 0. */
typedef struct mc_qi_t {
    int64_t num, den;
} mc_qi_t;

/* What the hook sees of each line with a pixel on the target, after its pixels are drawn; the
 * pointers hold only during the call. */
typedef struct mc_qi_line {
    uint32_t half;            /* the edge: half-edge of its first face (t = 0 at that face's corner k) */
    unsigned kind;            /* MC_EDGE_* */
    mc_raster_vertex a, b;    /* its projected corners, t = 0 at a */
    uint32_t qi[4];           /* QI_L(0+), QI_R(0+), QI_L(1-), QI_R(1-) */
    int exact;                /* computed face by face: changes not given */
    int visible_at_start;     /* V holds t = 0+ (then the changes alternate hidden, visible...) */
    uint32_t changes;         /* visibility changes, 0 < t < 1, increasing (without exact) */
    const mc_qi_t *change;
    uint32_t d;               /* its Bresenham steps D (line.h) */
    int from_b;               /* mc_line walks it from b: step i stands for t = 1 - i/D */
    uint32_t first, count;    /* its steps on the target: first .. first + count - 1 */
    const uint8_t *visible;   /* count bits, bit j (byte j/8, bit j%8): step first + j drawn */
} mc_qi_line;

typedef struct mc_qi_hook {
    void (*line)(void *user, const mc_qi_line *line);
    void *user;
} mc_qi_hook;

typedef struct mc_qi_stats {
    uint32_t edges, silhouettes, creases, borders;   /* as mc_lines_stats */
    uint32_t skipped;         /* always 0, as mc_lines_stats' (every line is drawn, clipped where it needs it) */
    uint32_t skipped_faces;   /* faces with a flagged corner (they hide nothing) */
    uint32_t clipped;         /* lines of a chosen kind with a flagged end, drawn clipped (as mc_lines_stats) */
    uint32_t clipped_away;    /* lines of a chosen kind with a flagged end of which clipping left nothing */
    uint32_t lines;           /* lines with a pixel on the target */
    uint32_t contours;        /* contours collected */
    uint32_t pixels;          /* pixels of those lines on the target: visible + hidden */
    uint32_t visible, hidden;
    uint32_t changes;         /* visibility changes found (lines not computed face by face) */
    uint32_t crossings;       /* contours crossing a line in front (QI changes) */
    uint32_t pair_tests;      /* line-contour tests past the bounding boxes */
    uint32_t ray_tests;       /* face tests past the bounding boxes: ray tests, face-by-face intervals */
    uint32_t exact_lines;     /* lines computed face by face */
    uint32_t grid_shift;      /* s: contour cells of 2^s pixels */
    uint32_t work_needed;     /* MC_QI_WORK_BYTES for this frame */
} mc_qi_stats;

/* Draws the level's lines of the kinds in flags (MC_EDGE_*, MC_LINES_NO_HIDING, MC_QI_FACE_BY_FACE)
 * seen through view into t, visible parts only (the pixels it does not draw keep what they hold).
 * hook and stats may be null. Returns MC_OK, MC_ERR_ARG (a null argument other than cache, hook, stats),
 * MC_ERR_SIZE (a side over MC_TARGET_MAX, or work too small: nothing drawn). */
int mc_mesh_qi(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, const mc_target *t,
               const mc_qi_buffers *buf, const mc_qi_hook *hook, mc_qi_stats *stats);

#endif
