/* Double-precision reference of the pinhole camera and pose (modelc/camera.h), for tests only:
 * the rotation of a quaternion normalized in doubles, the projection and depth mapping as the header
 * states them in real numbers, and the near-plane cut of a segment at its exact point. */
#ifndef MODELC_CAMERA_REF_H
#define MODELC_CAMERA_REF_H

#include <stdint.h>

typedef struct mc_ref_camera {
    double px, py, u0, v0;   /* pixels */
    double near, far;        /* um */
} mc_ref_camera;

/* c = R(q) p + t, q any non-zero quaternion (w, x, y, z) */
void mc_ref_pose_apply(const double q[4], const double t[3], const double p[3], double c[3]);

/* x, y on the target in 1/16 pixel (16 (u0 + px X / Z) + 8, ...) and the depth (0 at near, top at far,
 * affine in 1/Z) of camera point c, Z > 0 */
void mc_ref_camera_project(const mc_ref_camera *cam, const double c[3], double top, double *x, double *y, double *z);

/* the point of segment a b at Z = near (a's Z >= near > b's) */
void mc_ref_camera_cut(const mc_ref_camera *cam, const double a[3], const double b[3], double c[3]);

#endif
