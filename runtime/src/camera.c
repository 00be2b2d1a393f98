/* A pinhole camera and a rigid pose: see modelc/camera.h. */
#include "modelc/camera.h"
#include "modelc/fixed.h"    /* mc_div_round, mc_round_shift */
#include "modelc/target.h"   /* MC_OK, MC_DEPTH_EMPTY */

#define DEPTH_TOP (MC_DEPTH_EMPTY - 2u)

int mc_camera_init(mc_camera *c, int32_t px, int32_t py, int32_t u0, int32_t v0, uint16_t width, uint16_t height,
                   int32_t near, int32_t far)
{
    if (px <= 0 || py <= 0 || !width || !height || near <= 0 || far <= near) return MC_ERR_ARG;
    c->px = px, c->py = py, c->u0 = u0, c->v0 = v0;
    c->width = width, c->height = height;
    c->near = near, c->far = far;
    /* depth = DEPTH_TOP far (z - near) / ((far - near) z): 0 at near, DEPTH_TOP at far */
    c->zk = ((int64_t)DEPTH_TOP * far << 8) / ((int64_t)far - near);   /* below 2^16 2^8 2^31 */
    return MC_OK;
}

/* floor(sqrt(v)) */
static uint64_t isqrt64(uint64_t v)
{
    uint64_t r = 0, bit = (uint64_t)1 << 62;
    while (bit > v) bit >>= 2;
    while (bit) {
        if (v >= r + bit) {
            v -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return r;
}

int mc_quat_unit(const int32_t q[4], int32_t out[4])
{
    /* the quaternion scaled by a power of two until its largest component lies in [2^29, 2^30), then
     * made unit length in Q30: 2^58 <= n^2 < 2^62, so the integer square root is good to 2^-29 */
    int64_t v[4];
    uint32_t big = 0;
    for (int i = 0; i < 4; i++) {
        v[i] = q[i];
        const uint32_t m = q[i] < 0 ? 0u - (uint32_t)q[i] : (uint32_t)q[i];
        big |= m;
    }
    if (!big) return MC_ERR_ARG;
    int s = 0, up = 0;
    while ((big >> s) >= ((uint32_t)1 << 30)) s++;
    while ((big << up) < ((uint32_t)1 << 29)) up++;
    uint64_t n2 = 0;
    for (int i = 0; i < 4; i++) {
        v[i] = v[i] / ((int64_t)1 << s) * ((int64_t)1 << up);
        n2 += (uint64_t)(v[i] * v[i]);
    }
    int64_t n = (int64_t)isqrt64(n2);
    if (n2 - (uint64_t)(n * n) > (uint64_t)n) n++;   /* to nearest: n^2 + n is the midpoint's floor */
    for (int i = 0; i < 4; i++) out[i] = (int32_t)mc_div_round(v[i] * ((int64_t)1 << 30), n);
    return MC_OK;
}

int mc_pose_set(mc_pose *pose, const int32_t q[4], const int32_t t[3])
{
    int32_t u[4];
    if (mc_quat_unit(q, u) != MC_OK) return MC_ERR_ARG;
    const int64_t w = u[0], x = u[1], y = u[2], z = u[3];
    /* R = I + 2 [.]: each product of two Q30 components is below 2^61; sums of two, halved into Q30 */
#define Q30(e) ((int32_t)mc_round_shift((e), 29))
    pose->r[0][0] = (int32_t)((int64_t)1 << 30) - Q30(y * y + z * z);
    pose->r[0][1] = Q30(x * y - w * z);
    pose->r[0][2] = Q30(x * z + w * y);
    pose->r[1][0] = Q30(x * y + w * z);
    pose->r[1][1] = (int32_t)((int64_t)1 << 30) - Q30(x * x + z * z);
    pose->r[1][2] = Q30(y * z - w * x);
    pose->r[2][0] = Q30(x * z - w * y);
    pose->r[2][1] = Q30(y * z + w * x);
    pose->r[2][2] = (int32_t)((int64_t)1 << 30) - Q30(x * x + y * y);
#undef Q30
    for (int i = 0; i < 3; i++) pose->t[i] = t[i];
    return MC_OK;
}

void mc_pose_apply(const mc_pose *pose, const int32_t p[3], int32_t c[3])
{
    for (int i = 0; i < 3; i++) {
        const int64_t s = (int64_t)pose->r[i][0] * p[0] + (int64_t)pose->r[i][1] * p[1] + (int64_t)pose->r[i][2] * p[2];
        c[i] = (int32_t)(mc_round_shift(s, 30) + pose->t[i]);
    }
}

/* one image coordinate in 1/16 pixel: 16 (u0 + f x / z) + 8, clamped to the band */
static int32_t image_coord(int32_t f, int32_t u0, int32_t x, int32_t z, uint32_t *flags)
{
    /* 16 (u0 / 2^16 + f x / (2^16 z)) + 8 = (f x + u0 z + 2^15 z) / (2^12 z); numerator below 2^62 */
    const int64_t v = mc_div_round((int64_t)f * x + ((int64_t)u0 + 32768) * z, (int64_t)z << 12);
    const int64_t lim = (int64_t)MC_XFORM_BAND << MC_XFORM_SUBPIXEL_BITS;
    if (v > lim) { *flags |= MC_XFORM_FAR_OUT; return (int32_t)lim; }
    if (v < -lim) { *flags |= MC_XFORM_FAR_OUT; return (int32_t)-lim; }
    return (int32_t)v;
}

void mc_camera_project(const mc_camera *cam, const int32_t c[3], mc_xvertex *out)
{
    out->flags = 0;
    if (c[2] < cam->near) {
        out->flags = MC_XFORM_NEAR;
        out->x = out->y = 0;
        out->z = 0;
        return;
    }
    out->x = image_coord(cam->px, cam->u0, c[0], c[2], &out->flags);
    out->y = image_coord(cam->py, cam->v0, c[1], c[2], &out->flags);
    const int64_t z = mc_div_round(cam->zk * ((int64_t)c[2] - cam->near), (int64_t)c[2] << 8);
    out->z = z > (int64_t)DEPTH_TOP ? DEPTH_TOP : (uint32_t)z;
}

/* The point of segment a (z >= near) b (z < near) on the near plane: z = near exactly. */
static void cut(const mc_camera *cam, const int32_t a[3], const int32_t b[3], int32_t c[3])
{
    const int64_t num = (int64_t)a[2] - cam->near, den = (int64_t)a[2] - b[2];   /* 0 <= num < den */
    for (int i = 0; i < 2; i++) c[i] = (int32_t)((int64_t)a[i] + mc_div_round(((int64_t)b[i] - a[i]) * num, den));
    c[2] = cam->near;
}

int mc_camera_clip_segment(const mc_camera *cam, const int32_t a[3], const int32_t b[3], mc_xvertex out[2])
{
    const int ia = a[2] >= cam->near, ib = b[2] >= cam->near;
    if (!ia && !ib) return 0;
    int32_t c[3];
    if (ia) mc_camera_project(cam, a, &out[0]);
    else cut(cam, b, a, c), mc_camera_project(cam, c, &out[0]);
    if (ib) mc_camera_project(cam, b, &out[1]);
    else cut(cam, a, b, c), mc_camera_project(cam, c, &out[1]);
    return 1;
}

unsigned mc_camera_clip_triangle(const mc_camera *cam, const int32_t c[3][3], mc_xvertex out[4])
{
    unsigned n = 0;
    for (unsigned i = 0; i < 3; i++) {
        const int32_t *a = c[i], *b = c[(i + 1) % 3];
        const int ia = a[2] >= cam->near, ib = b[2] >= cam->near;
        if (ia) mc_camera_project(cam, a, &out[n++]);
        if (ia != ib) {
            int32_t p[3];
            if (ia) cut(cam, a, b, p);
            else cut(cam, b, a, p);   /* from the inside end: both faces of an edge cut it alike */
            mc_camera_project(cam, p, &out[n++]);
        }
    }
    return n < 3 ? 0 : n;
}
