/* A pinhole camera and a rigid pose, for tracking: where a point of a model lands in a camera image,
 * in the vertex format the rasterizer, the line walker and the sparse depth buffer take (xform.h
 * mc_xvertex), so that the tracker draws with the renderers' code.
 *
 * Units. Model and camera coordinates are micrometres in int32 (a model point and a translation each
 * within +-2^28 um, 268 m, per axis). Camera space as ViSP and OpenCV have it: x right, y down, z
 * forward; a pose maps a model point p to camera space as c = R p + t, R a rotation in Q30 built
 * from a unit quaternion. Intrinsics in Q16 pixels: px, py the focal lengths, u0, v0 the principal
 * point, in ViSP's pixel coordinates (u = u0 + px x / z, v = v0 + py y / z, pixel (i, j)'s centre at
 * u = i, v = j); on the target, whose pixel i spans [i, i + 1), that is x = u + 1/2, y = v + 1/2.
 *
 * Promise (mc_camera_project): for a point with z >= near: x and y in 1/16 pixel, the exact
 * projection of the rounded camera point rounded to nearest (halves away from zero), clamped to the
 * band +-MC_XFORM_BAND pixels and flagged MC_XFORM_FAR_OUT beyond it; z a 16-bit depth affine in
 * 1/z (so linear across a projected triangle), 0 at z = near and MC_DEPTH_EMPTY - 2 at z = far (and
 * beyond), within 1 unit of that mapping. A point with z < near is flagged MC_XFORM_NEAR and has no
 * position. The camera point c = R p + t is rounded to the micrometre; R, from the quaternion made
 * unit length in Q30, is within a few units of Q30 of the exact rotation, so c is within 4 um per
 * axis of the exact R p + t for |p| < 2^28 um (within 1 um for a model a metre across).
 *
 * Clipping: mc_camera_clip_segment cuts a segment in camera space at z = near (the cut exactly on
 * the plane, its x and y rounded to the micrometre) and projects what is left; mc_camera_clip_triangle
 * does the same to a triangle (Sutherland-Hodgman against one plane: at most 4 vertices). The band is
 * not clipped: a vertex beyond it (2^17 pixels off the image, which needs a point nearly 90 degrees
 * off the axis) is flagged, and callers leave out what has one.
 *
 * No heap, no floating point; one 64-bit division per projected point. Freestanding.
 */
#ifndef MODELC_CAMERA_H
#define MODELC_CAMERA_H

#include <stdint.h>
#include "xform.h"

typedef struct mc_camera {
    int32_t px, py, u0, v0;   /* Q16 pixels */
    uint16_t width, height;   /* the image */
    int32_t near, far;        /* um, 0 < near < far */
    int64_t zk;               /* depth: zk (z - near) / z, Q8 */
} mc_camera;

typedef struct mc_pose {
    int32_t r[3][3];          /* rotation, Q30 */
    int32_t t[3];             /* translation, um */
} mc_pose;

/* Sets a camera up; returns MC_OK, or MC_ERR_ARG for a focal length or side of 0 or near not in
 * (0, far). */
int mc_camera_init(mc_camera *c, int32_t px, int32_t py, int32_t u0, int32_t v0, uint16_t width, uint16_t height,
                   int32_t near, int32_t far);

/* q made unit length in Q30 (each component within about 1 unit of the exact one): out may be q.
 * Returns MC_OK, or MC_ERR_ARG for q = 0. */
int mc_quat_unit(const int32_t q[4], int32_t out[4]);

/* The pose of rotation q (w, x, y, z; Q30; normalized here, so any non-zero quaternion will do) and
 * translation t (um). Returns MC_OK, or MC_ERR_ARG for q = 0. */
int mc_pose_set(mc_pose *pose, const int32_t q[4], const int32_t t[3]);

/* c = R p + t, rounded to the micrometre. */
void mc_pose_apply(const mc_pose *pose, const int32_t p[3], int32_t c[3]);

/* The projection of camera point c (as promised above). */
void mc_camera_project(const mc_camera *cam, const int32_t c[3], mc_xvertex *out);

/* Segment a b in camera space cut at the near plane and projected: 1 with its ends in out (out[0]
 * on a's side), or 0 when all of it lies nearer than near. */
int mc_camera_clip_segment(const mc_camera *cam, const int32_t a[3], const int32_t b[3], mc_xvertex out[2]);

/* Triangle c0 c1 c2 in camera space cut at the near plane and projected: the polygon's vertices in
 * out in the triangle's turning order, their number returned (0, 3 or 4). */
unsigned mc_camera_clip_triangle(const mc_camera *cam, const int32_t c[3][3], mc_xvertex out[4]);

#endif
