/* Double-precision vertex projection and clipping: see xform_ref.h. */
#include "xform_ref.h"

#include <math.h>
#include <modelc/target.h>

#define TOP (MC_DEPTH_EMPTY - 2.0)
#define NEAR_D (1.0 / 64)

void mc_ref_view_point(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3], double q[3])
{
    mc_view v = mc_view_clamp(view, w, h);
    int32_t r30[3][3];
    mc_view_rotation(&v, r30);
    double pd[3] = {p[0] / 65536.0, p[1] / 65536.0, p[2] / 65536.0};
    for (int i = 0; i < 3; i++) q[i] = (r30[i][0] * pd[0] + r30[i][1] * pd[1] + r30[i][2] * pd[2]) / 1073741824.0;
}

mc_ref_vertex mc_ref_project_view(const mc_view *view, uint32_t w, uint32_t h, const double q[3])
{
    mc_view v = mc_view_clamp(view, w, h);
    double s = v.zoom / 65536.0 * (w < h ? w : h), cx = w / 2.0 + v.tx, cy = h / 2.0 + v.ty, eye = v.eye / 65536.0;
    mc_ref_vertex e = {0, 0, 0, 0, 0, 0};
    double mag = 1;
    if (v.projection == MC_PERSPECTIVE) {
        e.d = eye - q[2];
        if (e.d < NEAR_D) { e.near = 1; return e; }
        mag = eye / e.d;
        double half = 14529496.0 / 16777216.0, dmin = eye - half, dmax = eye + half;
        if (dmin < NEAR_D) dmin = NEAR_D;
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

mc_ref_vertex mc_ref_project(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3])
{
    double q[3];
    mc_ref_view_point(view, w, h, p, q);
    return mc_ref_project_view(view, w, h, q);
}

static int perspective(const mc_view *view, uint32_t w, uint32_t h)
{
    return mc_view_clamp(view, w, h).projection == MC_PERSPECTIVE;
}

static double eye_of(const mc_view *view, uint32_t w, uint32_t h) { return mc_view_clamp(view, w, h).eye / 65536.0; }

/* the view-space z of the near plane, rounded so that mc_ref_project_view takes it as in front */
static double near_z(double eye)
{
    double z = eye - NEAR_D;
    while (eye - z < NEAR_D) z = nextafter(z, -HUGE_VAL);
    return z;
}

/* the band's line k (0 left, 1 right, 2 top, 3 bottom) as a function inside where > 0, pixels */
static double band(int k, const mc_ref_vertex *v)
{
    const double b = MC_XFORM_BAND + 1.0 / 32;
    return k == 0 ? v->x + b : k == 1 ? b - v->x : k == 2 ? v->y + b : b - v->y;
}

/* the point at t from a to b on the screen: x, y, depth and 1/d linear there */
static mc_ref_vertex screen_lerp(const mc_ref_vertex *a, const mc_ref_vertex *b, double t)
{
    mc_ref_vertex c = *a;
    c.x = a->x + t * (b->x - a->x);
    c.y = a->y + t * (b->y - a->y);
    c.z = a->z + t * (b->z - a->z);
    c.d = 1 / (1 / a->d + t * (1 / b->d - 1 / a->d));
    c.near = 0;
    c.out = fabs(c.x) > MC_XFORM_BAND || fabs(c.y) > MC_XFORM_BAND;
    return c;
}

int mc_ref_clip_triangle(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3][3],
                         mc_ref_vertex out[MC_REF_CLIP_MAX])
{
    double q[MC_REF_CLIP_MAX + 1][3];
    int n = 3;
    for (int i = 0; i < 3; i++) mc_ref_view_point(view, w, h, p[i], q[i]);
    if (perspective(view, w, h)) {   /* near: d = eye - q.z >= 1/64, cut in view space */
        const double eye = eye_of(view, w, h);
        double c[MC_REF_CLIP_MAX + 1][3], f[3];
        int m = 0;
        for (int i = 0; i < 3; i++) f[i] = eye - q[i][2] - NEAR_D;
        for (int i = 0; i < 3; i++) {
            const int j = (i + 1) % 3;
            if (f[i] >= 0) c[m][0] = q[i][0], c[m][1] = q[i][1], c[m][2] = q[i][2], m++;
            if ((f[i] >= 0) != (f[j] >= 0)) {
                const double t = f[i] / (f[i] - f[j]);
                for (int k = 0; k < 3; k++) c[m][k] = q[i][k] + t * (q[j][k] - q[i][k]);
                c[m][2] = near_z(eye);   /* on the plane exactly */
                m++;
            }
        }
        if (m < 3) return 0;
        n = m;
        for (int i = 0; i < n; i++) q[i][0] = c[i][0], q[i][1] = c[i][1], q[i][2] = c[i][2];
    }
    mc_ref_vertex poly[2][MC_REF_CLIP_MAX + 4];
    int cur = 0;
    for (int i = 0; i < n; i++) poly[0][i] = mc_ref_project_view(view, w, h, q[i]);
    for (int k = 0; k < 4; k++) {
        int m = 0;
        for (int i = 0; i < n; i++) {
            const mc_ref_vertex *a = &poly[cur][i], *b = &poly[cur][(i + 1) % n];
            const double fa = band(k, a), fb = band(k, b);
            if (fa > 0) poly[cur ^ 1][m++] = *a;
            if ((fa > 0) != (fb > 0)) poly[cur ^ 1][m++] = screen_lerp(a, b, fa / (fa - fb));
            if (m > MC_REF_CLIP_MAX) return 0;
        }
        if (m < 3) return 0;
        n = m, cur ^= 1;
    }
    for (int i = 0; i < n; i++) out[i] = poly[cur][i];
    return n;
}

int mc_ref_clip_segment(const mc_view *view, uint32_t w, uint32_t h, const int32_t pa[3], const int32_t pb[3],
                        mc_ref_vertex out[2])
{
    double a[3], b[3];
    mc_ref_view_point(view, w, h, pa, a);
    mc_ref_view_point(view, w, h, pb, b);
    if (perspective(view, w, h)) {
        const double eye = eye_of(view, w, h), fa = eye - a[2] - NEAR_D, fb = eye - b[2] - NEAR_D;
        if (fa < 0 && fb < 0) return 0;
        if ((fa >= 0) != (fb >= 0)) {
            double *keep = fa >= 0 ? b : a;
            const double t = fa / (fa - fb);
            for (int k = 0; k < 3; k++) keep[k] = a[k] + t * (b[k] - a[k]);
            keep[2] = near_z(eye);
        }
    }
    out[0] = mc_ref_project_view(view, w, h, a);
    out[1] = mc_ref_project_view(view, w, h, b);
    double t0 = 0, t1 = 1;   /* Liang-Barsky against the band's lines */
    for (int k = 0; k < 4; k++) {
        const double f0 = band(k, &out[0]), f1 = band(k, &out[1]);
        if (f0 <= 0 && f1 <= 0) return 0;
        if (f0 <= 0 || f1 <= 0) {
            const double t = f0 / (f0 - f1);
            if (f0 <= 0) t0 = t > t0 ? t : t0;
            else t1 = t < t1 ? t : t1;
        }
    }
    if (!(t0 < t1)) return 0;
    const mc_ref_vertex e0 = out[0], e1 = out[1];
    if (t0 > 0) out[0] = screen_lerp(&e0, &e1, t0);
    if (t1 < 1) out[1] = screen_lerp(&e0, &e1, t1);
    return 1;
}

int mc_ref_front(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3][3])
{
    double q[3][3], a[3], b[3], n[3], c[3];
    for (int i = 0; i < 3; i++) mc_ref_view_point(view, w, h, p[i], q[i]);
    for (int i = 0; i < 3; i++) a[i] = q[1][i] - q[0][i], b[i] = q[2][i] - q[0][i];
    n[0] = a[1] * b[2] - a[2] * b[1], n[1] = a[2] * b[0] - a[0] * b[2], n[2] = a[0] * b[1] - a[1] * b[0];
    const double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    const double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    /* each view-space coordinate within 2^-31 of the runtime's, so each difference within 2^-30 */
    const double e = 2 * sqrt(3.0) * 0x1p-30;
    double v, tol;
    if (!perspective(view, w, h)) {
        v = n[2];
        tol = 2 * e * (la + lb) + 1e-12 * ln;
    } else {
        c[0] = -q[0][0], c[1] = -q[0][1], c[2] = eye_of(view, w, h) - q[0][2];
        v = c[0] * n[0] + c[1] * n[1] + c[2] * n[2];
        const double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        tol = 2 * (e * ln + lc * e * (la + lb)) + 1e-12 * lc * ln;
    }
    return v > tol ? 1 : v < -tol ? -1 : 0;
}
