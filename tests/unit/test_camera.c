/* The pinhole camera and pose (modelc/camera.h) against the double-precision reference
 * (runtime/ref/camera_ref.c):
 *   - mc_pose_set + mc_pose_apply: random quaternions of any size (unit, tiny, near the int32 limit,
 *     negative), points and translations up to 2^28 um: within 4 um of R(q) p + t per axis;
 *   - mc_camera_project: random cameras and camera points: x, y the exact projection of the integer
 *     point rounded to nearest (within 1/2 unit of 1/16 pixel, beyond rounding), z within 1 unit of
 *     the depth mapping, MC_XFORM_NEAR exactly when z < near, the band's flag and clamp;
 *   - mc_camera_clip_segment and mc_camera_clip_triangle: random segments and triangles across the
 *     near plane: what is left and its order, each cut on the plane within rounding of the exact cut;
 *   - mc_camera_init's and mc_pose_set's refusals.
 * Random numbers: PCG32 (modelc/rng.h) with fixed seeds.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <cmocka.h>

#include <modelc/camera.h>
#include <modelc/rng.h>
#include <modelc/target.h>
#include "../../runtime/ref/camera_ref.h"

#define TOP (MC_DEPTH_EMPTY - 2.0)

static int32_t range(mc_rng *r, int32_t lo, int32_t hi) { return lo + (int32_t)(mc_rng_next(r) % (uint32_t)(hi - lo + 1)); }

static void random_camera(mc_rng *r, mc_camera *c, mc_ref_camera *rc)
{
    const int32_t px = range(r, 50 << 16, 2000 << 16), py = px + range(r, -(20 << 16), 20 << 16);
    const uint16_t w = (uint16_t)range(r, 16, 1280), h = (uint16_t)range(r, 16, 960);
    const int32_t u0 = (int32_t)((w / 2) << 16) + range(r, -(30 << 16), 30 << 16);
    const int32_t v0 = (int32_t)((h / 2) << 16) + range(r, -(30 << 16), 30 << 16);
    const int32_t near = range(r, 1000, 100000), far = near + range(r, 1, 2000000000 - near);
    assert_int_equal(mc_camera_init(c, px, py, u0, v0, w, h, near, far), MC_OK);
    rc->px = px / 65536.0, rc->py = py / 65536.0, rc->u0 = u0 / 65536.0, rc->v0 = v0 / 65536.0;
    rc->near = near, rc->far = far;
}

static void test_pose(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 0xca3e, 1);
    double worst = 0;
    for (int i = 0; i < 200000; i++) {
        int32_t q[4], t[3], p[3];
        const int kind = i % 4;
        for (int k = 0; k < 4; k++) {
            q[k] = (int32_t)mc_rng_next(&r);
            if (kind == 1) q[k] >>= 20;   /* small components */
            if (kind == 2) q[k] = q[k] < 0 ? INT32_MIN + (int32_t)(mc_rng_next(&r) % 8) : INT32_MAX - (int32_t)(mc_rng_next(&r) % 8);
        }
        if (kind == 3) q[0] = 1 << 30, q[1] = q[2] = q[3] = 0, q[range(&r, 0, 3)] = range(&r, -3, 3);
        if (!(q[0] | q[1] | q[2] | q[3])) q[0] = 1;
        for (int k = 0; k < 3; k++) t[k] = range(&r, -(1 << 28), 1 << 28), p[k] = range(&r, -(1 << 28), 1 << 28);
        mc_pose pose;
        int32_t c[3];
        double qd[4] = {q[0], q[1], q[2], q[3]}, td[3] = {t[0], t[1], t[2]}, pd[3] = {p[0], p[1], p[2]}, cd[3];
        assert_int_equal(mc_pose_set(&pose, q, t), MC_OK);
        mc_pose_apply(&pose, p, c);
        mc_ref_pose_apply(qd, td, pd, cd);
        for (int k = 0; k < 3; k++) {
            const double e = fabs(c[k] - cd[k]);
            if (e > worst) worst = e;
            if (e > 4) fail_msg("pose %d: axis %d %d, reference %.3f", i, k, c[k], cd[k]);
        }
    }
    print_message("pose: worst error %.3f um\n", worst);
    int32_t zero[4] = {0, 0, 0, 0}, t[3] = {0, 0, 0};
    mc_pose pose;
    assert_int_equal(mc_pose_set(&pose, zero, t), MC_ERR_ARG);
}

/* v, the projection of integer camera point p (exact: p in doubles), against the reference */
static void check_vertex(const mc_ref_camera *rc, const int32_t p[3], const double exact[3], const mc_xvertex *v,
                         const char *what, int i)
{
    double x, y, z;
    mc_ref_camera_project(rc, exact, TOP, &x, &y, &z);
    const double lim = (double)MC_XFORM_BAND * 16;
    const int out = fabs(x) > lim + 0.5 || fabs(y) > lim + 0.5;
    if (out && !(v->flags & MC_XFORM_FAR_OUT)) fail_msg("%s %d: beyond the band, not flagged", what, i);
    if (v->flags & MC_XFORM_NEAR) fail_msg("%s %d: flagged near at z %d", what, i, p[2]);
    if (fabs(x) < lim - 1 && fabs(y) < lim - 1) {
        /* the projection of the integer point, rounded: within 1/2 unit */
        if (fabs(v->x - x) > 0.5 + 1e-9 || fabs(v->y - y) > 0.5 + 1e-9)
            fail_msg("%s %d: (%d %d), reference (%.3f %.3f)", what, i, v->x, v->y, x, y);
        if (v->flags) fail_msg("%s %d: flagged %u inside the band", what, i, v->flags);
    } else {
        if (abs(v->x) > (int32_t)lim || abs(v->y) > (int32_t)lim) fail_msg("%s %d: not clamped", what, i);
    }
    if (fabs(v->z - z) > 1) fail_msg("%s %d: depth %u, reference %.3f", what, i, v->z, z);
}

static void test_project(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 0xca3e, 2);
    mc_camera c;
    mc_ref_camera rc;
    for (int i = 0; i < 300000; i++) {
        if (i % 100 == 0) random_camera(&r, &c, &rc);
        int32_t p[3];
        const int32_t span = i % 3 == 0 ? 1 << 29 : 1 << 22;
        p[0] = range(&r, -span, span), p[1] = range(&r, -span, span);
        p[2] = i % 5 == 0 ? range(&r, -1000, c.near + 1000) : range(&r, c.near, 1 << 29);
        mc_xvertex v;
        mc_camera_project(&c, p, &v);
        if (p[2] < c.near) {
            assert_int_equal(v.flags, MC_XFORM_NEAR);
            continue;
        }
        const double e[3] = {p[0], p[1], p[2]};
        /* the integer point itself: x, y within 1/2 unit */
        double x, y, z;
        mc_ref_camera_project(&rc, e, TOP, &x, &y, &z);
        const double lim = (double)MC_XFORM_BAND * 16;
        if (fabs(x) < lim - 1 && fabs(y) < lim - 1) {
            if (fabs(v.x - x) > 0.5 + 1e-9 || fabs(v.y - y) > 0.5 + 1e-9)
                fail_msg("point %d: (%d %d), reference (%.4f %.4f)", i, v.x, v.y, x, y);
            assert_int_equal(v.flags, 0);
        } else {
            check_vertex(&rc, p, e, &v, "point", i);
        }
        if (fabs(v.z - z) > 1) fail_msg("point %d: depth %u, reference %.3f", i, v.z, z);
    }
}

/* whether camera point q (integer) is the segment's near cut: on the plane, within 1 um of the exact */
static void check_cut(const mc_ref_camera *rc, const double a[3], const double b[3], const mc_xvertex *v, int i)
{
    double c[3], x, y, z;
    mc_ref_camera_cut(rc, a, b, c);
    mc_ref_camera_project(rc, c, TOP, &x, &y, &z);
    /* 1 um of rounding, magnified by f / near pixels per um, plus the projection's own 1/2 unit */
    const double tol = 0.5 + 16.0 * (rc->px > rc->py ? rc->px : rc->py) / rc->near;
    const double lim = (double)MC_XFORM_BAND * 16;
    if (fabs(x) > lim + tol || fabs(y) > lim + tol) {   /* beyond the band: flagged and clamped */
        if (!(v->flags & MC_XFORM_FAR_OUT) || abs(v->x) > (int32_t)lim || abs(v->y) > (int32_t)lim)
            fail_msg("cut %d: beyond the band, flags %u (%d %d)", i, v->flags, v->x, v->y);
    } else if (fabs(x) < lim - tol && fabs(y) < lim - tol &&
               (fabs(v->x - x) > tol || fabs(v->y - y) > tol || v->flags)) {
        fail_msg("cut %d: (%d %d) flags %u, reference (%.3f %.3f)", i, v->x, v->y, v->flags, x, y);
    }
    if (v->z != 0) fail_msg("cut %d: depth %u on the near plane", i, v->z);
}

static void test_clip(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 0xca3e, 3);
    mc_camera c;
    mc_ref_camera rc;
    unsigned counts[5] = {0};
    for (int i = 0; i < 100000; i++) {
        if (i % 50 == 0) random_camera(&r, &c, &rc);
        int32_t t[3][3];
        for (int k = 0; k < 3; k++) {
            t[k][0] = range(&r, -200000, 200000), t[k][1] = range(&r, -200000, 200000);
            t[k][2] = c.near + range(&r, -c.near / 2, c.near);
        }
        double d[3][3];
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) d[k][j] = t[k][j];
        /* the segment t0 t1 */
        mc_xvertex s[2];
        const int ia = t[0][2] >= c.near, ib = t[1][2] >= c.near;
        const int kept = mc_camera_clip_segment(&c, t[0], t[1], s);
        assert_int_equal(kept, ia || ib);
        if (kept) {
            if (ia) check_vertex(&rc, t[0], d[0], &s[0], "segment end", i);
            else check_cut(&rc, d[1], d[0], &s[0], i);
            if (ib) check_vertex(&rc, t[1], d[1], &s[1], "segment end", i);
            else check_cut(&rc, d[0], d[1], &s[1], i);
        }
        /* the triangle: its inside corners and its cuts, in turning order */
        mc_xvertex poly[4];
        const unsigned n = mc_camera_clip_triangle(&c, (const int32_t(*)[3])t, poly);
        unsigned inside = 0, m = 0;
        for (int k = 0; k < 3; k++) inside += t[k][2] >= c.near;
        assert_int_equal(n, inside == 0 ? 0 : inside == 2 ? 4 : 3);
        counts[n]++;
        if (!n) continue;
        for (int k = 0; k < 3; k++) {
            const int kn = (k + 1) % 3, ik = t[k][2] >= c.near, in = t[kn][2] >= c.near;
            if (ik) check_vertex(&rc, t[k], d[k], &poly[m++], "triangle corner", i);
            if (ik != in) {
                if (ik) check_cut(&rc, d[k], d[kn], &poly[m++], i);
                else check_cut(&rc, d[kn], d[k], &poly[m++], i);
            }
        }
        assert_int_equal(m, n);
    }
    /* every case met */
    assert_true(counts[0] > 100 && counts[3] > 100 && counts[4] > 100);
}

static void test_refusals(void **state)
{
    (void)state;
    mc_camera c;
    assert_int_equal(mc_camera_init(&c, 0, 1 << 16, 0, 0, 8, 8, 10, 20), MC_ERR_ARG);
    assert_int_equal(mc_camera_init(&c, 1 << 16, -1, 0, 0, 8, 8, 10, 20), MC_ERR_ARG);
    assert_int_equal(mc_camera_init(&c, 1 << 16, 1 << 16, 0, 0, 0, 8, 10, 20), MC_ERR_ARG);
    assert_int_equal(mc_camera_init(&c, 1 << 16, 1 << 16, 0, 0, 8, 8, 0, 20), MC_ERR_ARG);
    assert_int_equal(mc_camera_init(&c, 1 << 16, 1 << 16, 0, 0, 8, 8, 20, 20), MC_ERR_ARG);
    assert_int_equal(mc_camera_init(&c, 1 << 16, 1 << 16, 0, 0, 8, 8, 10, 20), MC_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pose),
        cmocka_unit_test(test_project),
        cmocka_unit_test(test_clip),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
