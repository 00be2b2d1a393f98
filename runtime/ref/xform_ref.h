/* Double-precision reference of the vertex projection (modelc/xform.h mc_xform_vertex), for tests
 * only: the same clamped view and Q30 rotation, everything after it in doubles.
 *
 * Clipping (xform.h's clip region, for tests of mc_mesh_render's and mc_mesh_lines' clipped faces
 * and lines): in perspective the near plane d >= 1/64 cube side is cut in view space; then the
 * projected polygon or segment is cut against the band's lines x, y = -+(MC_XFORM_BAND + 1/32) pixel on
 * the screen. The band's planes pass through the eye, so cutting the image of a figure in front of
 * the eye against their lines is cutting the figure against the planes; depth and 1/d are affine
 * along the image of a plane (xform.h), so the screen cuts interpolate them linearly. Exact up to
 * double rounding, from the unrounded rotation (the runtime rounds view space to Q30: 2^-31 cube side). */
#ifndef MODELC_XFORM_REF_H
#define MODELC_XFORM_REF_H

#include <stdint.h>
#include <modelc/xform.h>

typedef struct mc_ref_vertex {
    double x, y, z, d;   /* pixels; depth units; distance from the eye (cube sides) */
    int near, out;       /* before the near plane (no position); beyond the guard band */
} mc_ref_vertex;

/* p: unit-cube Q16 coordinates (pmesh.h), seen through view on a w x h target. */
mc_ref_vertex mc_ref_project(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3]);

/* p's view-space point q (cube sides; the eye on +z at distance eye, xform.h), as mc_ref_project
 * takes it, and the projection of such a point (mc_ref_project(p) is mc_ref_project_view(q)). */
void mc_ref_view_point(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3], double q[3]);
mc_ref_vertex mc_ref_project_view(const mc_view *view, uint32_t w, uint32_t h, const double q[3]);

/* The triangle of corners p (unit-cube Q16) clipped: its polygon's vertices (at most 8: a triangle
 * gains at most one a plane) in the triangle's turning order, projected; returns their number, 0 when
 * less than a polygon is left. */
#define MC_REF_CLIP_MAX 8
int mc_ref_clip_triangle(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3][3],
                         mc_ref_vertex out[MC_REF_CLIP_MAX]);

/* The segment pa pb (unit-cube Q16) clipped: 1 with its ends projected in out (out[0] on pa's side),
 * or 0 when nothing (or a single point) is left. */
int mc_ref_clip_segment(const mc_view *view, uint32_t w, uint32_t h, const int32_t pa[3], const int32_t pb[3],
                        mc_ref_vertex out[2]);

/* The facing of the triangle of corners p by its plane (xform.h mc_xform_front: the eye strictly in
 * front of it; orthographic, its normal's z > 0): 1 front, -1 not, 0 when the runtime's Q30 view
 * space (each coordinate within 2^-31 of these) could make it either. */
int mc_ref_front(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3][3]);

#endif
