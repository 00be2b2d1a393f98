/* Double-precision vertex projection: see xform_ref.h. */
#include "xform_ref.h"

#include <math.h>
#include <modelc/target.h>

#define TOP (MC_DEPTH_EMPTY - 2.0)

mc_ref_vertex mc_ref_project(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3])
{
    mc_view v = mc_view_clamp(view, w, h);
    int32_t r30[3][3];
    mc_view_rotation(&v, r30);
    double q[3], pd[3] = {p[0] / 65536.0, p[1] / 65536.0, p[2] / 65536.0};
    for (int i = 0; i < 3; i++) q[i] = (r30[i][0] * pd[0] + r30[i][1] * pd[1] + r30[i][2] * pd[2]) / 1073741824.0;
    double s = v.zoom / 65536.0 * (w < h ? w : h), cx = w / 2.0 + v.tx, cy = h / 2.0 + v.ty, eye = v.eye / 65536.0;
    mc_ref_vertex e = {0, 0, 0, 0, 0, 0};
    double mag = 1;
    if (v.projection == MC_PERSPECTIVE) {
        e.d = eye - q[2];
        if (e.d < 1.0 / 64) { e.near = 1; return e; }
        mag = eye / e.d;
        double half = 14529496.0 / 16777216.0, dmin = eye - half, dmax = eye + half;
        if (dmin < 1.0 / 64) dmin = 1.0 / 64;
        e.z = TOP * dmax / (dmax - dmin) * (e.d - dmin) / e.d;
        if (e.z < 0) e.z = 0;
    } else {
        e.d = 1 - q[2];
        e.z = (0.875 - q[2]) * 32768.0;
    }
    e.x = cx + s * q[0] * mag;
    e.y = cy - s * q[1] * mag;
    e.out = fabs(e.x) > MC_XFORM_BAND || fabs(e.y) > MC_XFORM_BAND;
    return e;
}
