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
 * (see mc_view_clamp): zoom to [1/64, 64] and to a screen extent of at most MC_COORD_LIMIT / 2 pixels,
 * translations to +-MC_COORD_LIMIT / 4 pixels, the perspective eye distance to [1/16, 256] cube sides.
 *
 * Representable ranges (MC_COORD_LIMIT = 2^(30 - MC_FRAC_BITS) pixels; at the default MC_FRAC_BITS 15:
 * 32768 pixels), all enforced by mc_view_clamp and the renderers, never by wrapping:
 *   - largest model extent on screen: the bounding cube's side S = zoom * min(width, height) is at
 *     most MC_COORD_LIMIT / 2 pixels (16384 at F = 15), so the bounding sphere (S * sqrt(3) / 2) plus
 *     half the screen plus the translation stays below MC_COORD_LIMIT and every fixed-point sum on
 *     the rendering path stays below 2^30 (half the int32 range). The model itself is always scaled
 *     into the unit cube by the generator, so this is the only extent limit;
 *   - largest zoom: min(64, MC_COORD_LIMIT / 2 / min(width, height)): at F = 15, 64 for short sides
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
 * against these (raster.h, line.h take coordinates inside the band). */
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

#endif
