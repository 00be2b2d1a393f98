/* View transforms: a camera (rotation, zoom, translation, projection) and what it means in fixed point.
 *
 * Promise: mc_view is the camera only, the same for every part a model has (what a renderer draws
 * per leaf or per line is its own options' business, e.g. octree_render.h's mc_octree_options).
 * mc_view_clamp turns any mc_view into one every renderer can draw without overflow, and
 * mc_view_rotation gives its exact Q30 rotation matrix.
 *
 * The model's bounding cube is centred on the screen; at zoom 1 its side spans the shorter side of
 * the target. Screen x grows to the right, y downwards; the model's +y is up and +z faces the viewer
 * at yaw = pitch = roll = 0. Rotation is R = Rz(roll) * Rx(pitch) * Ry(yaw), rebuilt from the integer
 * angles every frame.
 *
 * Any values are accepted. Values the fixed-point format cannot represent are clamped, never wrapped
 * (see mc_view_clamp): zoom to [1/64, 64] and to a screen extent of at most MC_VIEW_EXTENT_MAX pixels,
 * translations to +-MC_COORD_LIMIT / 4 pixels, the perspective eye distance to [1/16, 256] cube sides.
 *
 * Representable ranges (MC_COORD_LIMIT = 2^(30 - MC_FRAC_BITS) pixels; at the default MC_FRAC_BITS 15:
 * 32768 pixels), all enforced by mc_view_clamp and the renderers, never by wrapping:
 *   - largest model extent on screen: the bounding cube's side S = zoom * min(width, height) is at
 *     most MC_VIEW_EXTENT_MAX pixels: MC_COORD_LIMIT / 2 (16384 at F = 15), so the bounding sphere
 *     (S * sqrt(3) / 2) plus half the screen plus the translation stays below MC_COORD_LIMIT and every
 *     fixed-point sum on the rendering path stays below 2^30 (half the int32 range); and never above
 *     2^16 pixels (a bound only below F = 13), so that a mesh vertex's projection, S in Q16 times a
 *     Q30 view-space coordinate, stays below 2^62. The model itself is always scaled into the unit
 *     cube by the generator, so this is the only extent limit;
 *   - largest zoom: min(64, MC_VIEW_EXTENT_MAX / min(width, height)): at F = 15, 64 for short sides
 *     up to 256 pixels, 34 and a fraction at 480 pixels, 4 at MC_TARGET_MAX (4096 pixels); smallest zoom 1/64;
 *   - translations: +-MC_COORD_LIMIT / 4 pixels (+-8192 at F = 15), far enough to move the model
 *     wholly off any target;
 *   - target sides: 1..MC_TARGET_MAX pixels (4096 at F = 15; renderers refuse larger targets, target.h);
 *   - perspective eye distance: [1/16, 256] cube sides; inside the model's bounding sphere (below
 *     sqrt(3)/2) parts of the model lie behind the eye and are not drawn; points nearer than 1/64
 *     cube side in front of the eye are not drawn either (the near plane);
 *   - angles: any int32 (taken modulo a turn).
 * tests/stress/stress.c renders random views across and beyond these ranges and checks that nothing
 * is written outside the target and every point lies within a stated bound of its exact position.
 */
#ifndef MODELC_XFORM_H
#define MODELC_XFORM_H

#include <stdint.h>
#include "fixed.h"
#include "trig.h"

typedef enum mc_projection { MC_ORTHOGRAPHIC = 0, MC_PERSPECTIVE = 1 } mc_projection;

typedef struct mc_view {
    int32_t yaw, pitch, roll;   /* MC_ANGLE_FULL units per turn */
    int32_t zoom;               /* Q16: 65536 = 1 */
    int32_t tx, ty;             /* pixels, applied after projection */
    mc_projection projection;
    int32_t eye;                /* perspective only: eye distance from the model centre, Q16 cube sides */
} mc_view;

#define MC_ZOOM_ONE 65536
#define MC_ZOOM_MIN (MC_ZOOM_ONE / 64)
#define MC_ZOOM_MAX (MC_ZOOM_ONE * 64)
#define MC_EYE_MIN (MC_ZOOM_ONE / 16)
#define MC_EYE_MAX (MC_ZOOM_ONE * 256)
/* The largest screen extent of the model's cube, pixels (see above). */
#define MC_VIEW_EXTENT_MAX (MC_COORD_LIMIT / 2 < 65536 ? MC_COORD_LIMIT / 2 : 65536)

/* Frontal, zoom 1, orthographic, eye 2 cube sides away. */
mc_view mc_view_default(void);

/* The view the renderer really draws for a target of width x height pixels: v with every field
 * clamped to what the fixed-point format represents (projections other than MC_PERSPECTIVE become
 * MC_ORTHOGRAPHIC). */
mc_view mc_view_clamp(const mc_view *v, uint32_t width, uint32_t height);

/* Rotation matrix for the view's angles, Q30 entries (row-major r[row][col]). */
void mc_view_rotation(const mc_view *v, int32_t r[3][3]);

/* ---- Vertex projection (meshes and edge models) ------------------------------------------------
 * Promise: mc_xform_vertex puts a unit-cube point where the point renderer puts a leaf at that
 * position (the same clamped view, rotation and scale; runtime/ref/ref.c states it in doubles):
 *   q = R p,  orthographic: x = cx + S q.x,  y = cy - S q.y
 *             perspective:  the same with S * eye / (eye - q.z)
 * with S = zoom * min(width, height) pixels per cube side and (cx, cy) = (width/2 + tx, height/2 + ty).
 * x and y come in 1/16 pixel (MC_XFORM_SUBPIXEL_BITS, raster.h's subpixel), rounded to nearest from
 * the fixed-point values, within 1/16 pixel of the exact (real-number) projection with the same
 * Q30 rotation. z is a 16-bit depth, smaller nearer, from 0 up to at most MC_DEPTH_EMPTY - 2:
 *   orthographic: (7/8 - q.z) * 2^15, one unit 1/32768 cube side, for any zoom;
 *   perspective: affine in 1/distance (so it is linear across a projected triangle, as a z-buffer
 *     needs), 0 at the nearest distance a unit-cube point can have and MC_DEPTH_EMPTY - 2 at the
 *     farthest, within 1 unit of the exact mapping.
 * A point nearer the eye than the near plane (1/64 cube side, as the point renderer) is flagged
 * MC_XFORM_NEAR and has no screen position; a point whose position would leave +-MC_XFORM_BAND
 * pixels (a guard band far beyond any target: near the eye perspective magnifies without bound) is
 * flagged MC_XFORM_FAR_OUT and its x, y are clamped to the band. Callers clip triangles and lines
 * with a flagged corner against these (below: raster.h, line.h take coordinates inside the band). */
#define MC_XFORM_SUBPIXEL_BITS 4
#define MC_XFORM_BAND ((int32_t)1 << 17)
enum { MC_XFORM_NEAR = 1, MC_XFORM_FAR_OUT = 2 };

typedef struct mc_xform {
    int32_t r[3][3];         /* Q30 rotation */
    int64_t scale;           /* S, Q16 pixels per cube side */
    int64_t cx, cy;          /* the cube centre on screen, 1/16 pixel */
    int32_t perspective;     /* 0 or 1 */
    int64_t eye;             /* eye distance, Q30 cube sides */
    int64_t dmin, za;        /* perspective depth: za * (d - dmin) / d, dmin Q24, za Q8 */
} mc_xform;

typedef struct mc_xvertex {
    int32_t x, y;            /* 1/16 pixel */
    uint32_t z;              /* depth, 0 .. MC_DEPTH_EMPTY - 2 */
    uint32_t flags;          /* MC_XFORM_NEAR, MC_XFORM_FAR_OUT */
} mc_xvertex;

/* Sets up the projection of view v (clamped, mc_view_clamp) onto a width x height target. */
void mc_xform_init(mc_xform *x, const mc_view *v, uint32_t width, uint32_t height);
/* Projects p, unit-cube coordinates in Q16 (-32768 .. 32767 for -1/2 .. 1/2, pmesh.h's positions). */
void mc_xform_vertex(const mc_xform *x, const int32_t p[3], mc_xvertex *out);

/* Where an orthographic view puts a box of points: for every p with lo[k] <= p[k] <= hi[k] (unit-cube
 * Q16, as mc_xform_vertex takes it), mc_xform_vertex gives x0 <= x <= x1, y0 <= y <= y1 and z >= z0,
 * no flag. */
typedef struct mc_xform_box {
    int32_t x0, x1, y0, y1;  /* 1/16 pixel */
    uint32_t z0;             /* the least depth */
} mc_xform_box;
/* Sets *b for the box lo .. hi (lo[k] <= hi[k]) and returns 1; returns 0 in a perspective view, or
 * when a point of the box may leave the band (then *b says nothing). Exact bounds: each coordinate
 * is a rounding of a linear form, monotone, taken at the box's corner where the form is least or
 * greatest. */
int mc_xform_box_bound(const mc_xform *x, const int32_t lo[3], const int32_t hi[3], mc_xform_box *b);

/* ---- Clipping (faces and lines with a flagged corner) --------------------------------------------
 * Promise: the part of a triangle or a segment inside the clip region, cut in view space and
 * projected as mc_xform_vertex projects a point, so that what is left can be drawn: every vertex
 * inside the band and none flagged MC_XFORM_NEAR.
 *
 * View space: mc_xform_view gives q = R p in Q30 cube sides (|q| < 2^30) rounded as mc_xform_vertex
 * rounds it, and mc_xform_project is mc_xform_vertex's projection of a point q: mc_xform_vertex(p)
 * and mc_xform_project(mc_xform_view(p)) are the same bytes. d = eye - q.z, the distance from the eye.
 * The functions below take such points of the unit cube (or points between them: the cube's sphere,
 * |q| <= sqrt(3)/2); at the default MC_FRAC_BITS any |q.x|, |q.y|, |q.z| < 2^30 will do.
 *
 * Clip region: five half-spaces, taken in this order:
 *   near    d >= 1/64 cube side (perspective only: an orthographic view has no near plane);
 *   left, right, top, bottom   x > -b, x < b, y > -b, y < b (strictly) with b = MC_XFORM_BAND + 1/32
 *           pixel, for the projection x = cx + S eye q.x / d, y = cy - S eye q.y / d (orthographic:
 *           without eye / d), S eye q taken as mc_xform_vertex rounds it (to 2^-34 pixel cube side;
 *           orthographic S q to 2^-34 of 1/16 pixel, towards minus infinity on the plane's side).
 *           Multiplied by d each is linear in q up to that rounding; the four pass through the eye.
 * A point lies outside the near plane exactly when mc_xform_vertex flags it MC_XFORM_NEAR, and
 * outside a band plane exactly when its rounded position passes the band on that side (flagged
 * MC_XFORM_FAR_OUT): a coordinate rounded to nearest, halves away from zero, passes MC_XFORM_BAND
 * exactly when the unrounded one reaches 1/32 pixel beyond it. So a corner left unflagged is inside
 * every plane, and an edge between two such corners is never cut.
 *
 * mc_xform_clip_triangle (Sutherland-Hodgman): the polygon, at first the triangle q0 q1 q2, is cut
 * by each plane that one of the three corners lies outside, in the order above: it keeps its
 * vertices inside the plane and gains a cut where an edge crosses it. A convex polygon gains at
 * most one vertex a plane: at most 3 + 5 = MC_XFORM_CLIP_MAX vertices, projected into out in the
 * triangle's turning order. Returns their number, or 0 (out untouched) when nothing is left: every
 * corner outside one plane (wholly behind the near plane or beyond one side of the band), or no
 * vertex inside after a cut. (Rounded cuts can leave a polygon a hair non-convex, and a later cut
 * then add two vertices; that needs a vertex within a few 2^-30 cube side of two planes at once.
 * Should a polygon pass MC_XFORM_CLIP_MAX vertices, the triangle is dropped: 0.)
 * mc_xform_clip_segment: the segment a b cut by the same planes in the same order. Returns 0 when
 * nothing is left (at some plane both ends lie outside), else 1 with out[0] on a's side and out[1]
 * on b's. Its cuts are, bit for bit, the cut vertices a triangle with that edge has on it (short of
 * a cut within rounding of a second plane, which the triangle may cut again where the segment is
 * not: a corner of the triangle outside that plane makes it apply the plane).
 *
 * Cuts. The edge between a vertex a inside a plane and a vertex b outside it is cut at
 * c = a + t (b - a), t = f(a) / (f(a) - f(b)), f the plane's function as evaluated above, always
 * from the inside end: faces sharing an edge, and the segment on it, cut it at the same point. t is
 * taken to within 2^-31 (the one division, 64 by 32 bits: both f values shifted right until the
 * divisor fits 32 bits), each coordinate of c rounded to nearest in Q30, between a's and b's: c is
 * within |b - a| 2^-31 + 2^-31 < 11/8 2^-30 cube side, along each axis, of the point at t of the
 * edge. Near-plane cuts are exact before that rounding (f changes by under 2^31 along any edge) and
 * lie at d = 1/64 exactly. Hence every vertex has d >= 1/64 (corners inside, near cuts on it, later
 * cuts between two such vertices): none is flagged MC_XFORM_NEAR. A band cut lies 1/32 pixel beyond
 * the band up to its error (below, far under 1/32 pixel across the plane): its projection rounds onto
 * the band or one unit beyond and is clamped as mc_xform_vertex clamps, so its coordinate across
 * the band is +-MC_XFORM_BAND exactly (and MC_XFORM_FAR_OUT may be set). So every vertex has |x|,
 * |y| <= MC_XFORM_BAND * 16 = 2^21 in 1/16 pixel: within raster.h's MC_RASTER_COORD_LIMIT (2^22),
 * and in whole pixels (x >> 4) within line.h's MC_LINE_COORD_MAX (2^24).
 *
 * Accuracy, against the exact cut (the same planes and cuts in real numbers from the same Q30
 * corners). An error of e cube side along each axis moves a projected point by at most
 * e (S eye + |x - cx|) / d pixels in x (y likewise; orthographic e S). At MC_FRAC_BITS 15 (the
 * default) and above (S <= 2^14 pixels, eye / d <= 57 as d >= 1/64 and d >= eye - sqrt(3)/2,
 * |x - cx| <= 9/8 2^17 pixels in the region) that is under 10 e 2^20 pixels: under 1/4 of 1/16 pixel
 * for the cuts' e < 11/8 2^-30 (at MC_FRAC_BITS 12, S <= 2^17: under 1/2 of it). The rounding of
 * S eye q moves a plane by under 2^-24 of 1/16 pixel across it. So, at MC_FRAC_BITS 15 and above,
 * with the projection's own rounding (1/32 pixel):
 *   - a near cut is within 1/32 pixel + 2^-7 of 1/16 pixel of the exact cut, in x and y;
 *   - a band cut of an edge between two corners is within 1/16 pixel in x and y, wherever the
 *     projected edge crosses the band's line at an angle theta with sin(theta) >= 2^-22 (the plane's
 *     error moves the cut along the edge by its size over sin(theta));
 *   - a cut of an edge an earlier plane made carries its ends' errors as well, the part across the
 *     plane's line over sin(theta).
 * Depth: the projection's, within 1 unit of the exact mapping at the vertex's point, which its error
 * moves by under 1/64 unit (plus the depth's slope along the edge times any movement along it).
 * Everything here holds for MC_FRAC_BITS 12 and above, where mc_xform_vertex's own products fit 64
 * bits: f stays below 2^62.
 *
 * mc_xform_front: whether the eye lies strictly on the front side of the plane of q0, q1, q2 (turning
 * counter-clockwise seen from the eye): (e - q0) . ((q1 - q0) x (q2 - q0)) > 0 with e = (0, 0, eye)
 * (orthographic: the normal's z > 0), exact in integers (64-bit products, their sum in 128 bits). For
 * a triangle wholly in front of the eye it is the sign of its exact projected area: the facing
 * mc_raster_triangle culls by, before rounding to 1/16 pixel. It needs no projection, so corners
 * behind the eye are fine, and it is the same however the triangle is cut.
 *
 * No heap, no floating point, no recursion; stack: two polygons of MC_XFORM_CLIP_MAX Q30 points and
 * their plane values (about 300 bytes). Freestanding. */
#define MC_XFORM_CLIP_MAX 8

/* q = R p (Q30 cube sides) for p in unit-cube Q16, as mc_xform_vertex rounds it. */
void mc_xform_view(const mc_xform *x, const int32_t p[3], int32_t q[3]);
/* The projection of view-space point q (Q30, |q| < 2^30), as mc_xform_vertex projects a point. */
void mc_xform_project(const mc_xform *x, const int32_t q[3], mc_xvertex *out);
/* The triangle q0 q1 q2 (view space) clipped; returns the number of vertices in out (0: none). */
unsigned mc_xform_clip_triangle(const mc_xform *x, const int32_t q[3][3], mc_xvertex out[MC_XFORM_CLIP_MAX]);
/* The segment a b (view space) clipped: 1 with its ends in out, or 0 when nothing is left. */
int mc_xform_clip_segment(const mc_xform *x, const int32_t a[3], const int32_t b[3], mc_xvertex out[2]);
/* 1 when the triangle q0 q1 q2 (view space) faces the eye, else 0. */
int mc_xform_front(const mc_xform *x, const int32_t q[3][3]);

#endif
