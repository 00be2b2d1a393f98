/* Double-precision camera and pose: see camera_ref.h. */
#include "camera_ref.h"

#include <math.h>

void mc_ref_pose_apply(const double q[4], const double t[3], const double p[3], double c[3])
{
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    const double r[3][3] = {
        {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
        {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
        {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)},
    };
    for (int i = 0; i < 3; i++) c[i] = r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + t[i];
}

void mc_ref_camera_project(const mc_ref_camera *cam, const double c[3], double top, double *x, double *y, double *z)
{
    *x = 16 * (cam->u0 + cam->px * c[0] / c[2]) + 8;
    *y = 16 * (cam->v0 + cam->py * c[1] / c[2]) + 8;
    double d = top * cam->far * (c[2] - cam->near) / ((cam->far - cam->near) * c[2]);
    *z = d > top ? top : d;
}

void mc_ref_camera_cut(const mc_ref_camera *cam, const double a[3], const double b[3], double c[3])
{
    const double s = (a[2] - cam->near) / (a[2] - b[2]);
    for (int i = 0; i < 3; i++) c[i] = a[i] + (b[i] - a[i]) * s;
    c[2] = cam->near;
}
