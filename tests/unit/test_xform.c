/* Vertex projection (xform.h mc_xform_vertex) against the same projection in doubles, as
 * runtime/ref/ref.c states it for the point renderer, with the view's own Q30 rotation converted to
 * double (so what is measured is the fixed-point projection, not the sine table):
 *   - screen x, y within 1/16 pixel of the exact value wherever the point is inside the guard band;
 *   - the depth within 1 unit of its formula (orthographic (7/8 - q.z) * 2^15; perspective
 *     DEPTH_TOP * k * (d - dmin) / d), inside 0 .. MC_DEPTH_EMPTY - 2, and strictly ordered with the
 *     distance wherever the exact depths differ by more than 2 units;
 *   - MC_XFORM_NEAR exactly for points nearer than 1/64 cube side (away from the boundary by 2^-20),
 *     MC_XFORM_FAR_OUT exactly for points beyond the band, their x, y clamped to it;
 * over random views across and beyond mc_view_clamp's ranges (zoom 1/128..128, eye 1/32..512,
 * translations, target sides 1..4096) and random points of the unit cube, its corners included;
 * and, orthographic, the inline step the mesh loops use (xform_ortho.h) equal to it bit for bit;
 * mc_xform_box_bound against the corners of random boxes and points inside them;
 * and xform_ortho.h's two branch-free roundings (v / 2^s to nearest, halves away from zero) against
 * the same rounding in 128-bit integers, over every shift they serve, halves and the extremes of
 * their ranges included.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include <modelc/rng.h>
#include <modelc/target.h>
#include <modelc/xform.h>
#include "../../runtime/ref/xform_ref.h"
#include "../../runtime/src/xform_ortho.h"


static int32_t rnd(mc_rng *g, int32_t lo, int32_t hi)
{
    return lo + (int32_t)(mc_rng_next(g) % (uint32_t)(hi - lo + 1));
}

typedef mc_ref_vertex exact;

static exact project(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3])
{
    return mc_ref_project(view, w, h, p);
}

static mc_view random_view(mc_rng *g, int perspective)
{
    mc_view v = mc_view_default();
    v.yaw = rnd(g, -100000, 100000);
    v.pitch = rnd(g, -100000, 100000);
    v.roll = rnd(g, -100000, 100000);
    v.zoom = (int32_t)(65536.0 * pow(2.0, rnd(g, -7000, 7000) / 1000.0));
    v.tx = rnd(g, 0, 3) ? rnd(g, -300, 300) : rnd(g, -20000, 20000);
    v.ty = rnd(g, 0, 3) ? rnd(g, -300, 300) : rnd(g, -20000, 20000);
    v.projection = perspective ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
    v.eye = (int32_t)(65536.0 * pow(2.0, rnd(g, -5000, 9000) / 1000.0));
    return v;
}

static void random_point(mc_rng *g, int32_t p[3])
{
    for (int k = 0; k < 3; k++)
        p[k] = rnd(g, 0, 7) ? rnd(g, -32768, 32767) : (rnd(g, 0, 1) ? 32767 : -32768);
}

static void check_views(int perspective, int views, int points)
{
    mc_rng g;
    mc_rng_seed(&g, 1234 + (uint64_t)perspective, 77);
    long checked = 0, near = 0, out = 0;
    for (int k = 0; k < views; k++) {
        mc_view v = random_view(&g, perspective);
        uint32_t w = (uint32_t)(rnd(&g, 0, 4) ? rnd(&g, 1, 640) : rnd(&g, 1, 4096));
        uint32_t h = (uint32_t)(rnd(&g, 0, 4) ? rnd(&g, 1, 480) : rnd(&g, 1, 4096));
        mc_xform x;
        mc_xform_init(&x, &v, w, h);
        mc_xform_ortho xo;
        mc_xform_ortho_init(&xo, &x);
        mc_xvertex prev = {0, 0, 0, 0};
        exact eprev = {0, 0, 0, 0, 0, 0};
        for (int i = 0; i < points; i++) {
            int32_t p[3];
            random_point(&g, p);
            mc_xvertex o;
            mc_xform_vertex(&x, p, &o);
            if (!perspective) {
                mc_xvertex io;
                mc_xform_ortho_point(&xo, p, &io);
                if (io.x != o.x || io.y != o.y || io.z != o.z || io.flags != o.flags)
                    fail_msg("view %d point %d: the inline step gives (%d, %d, %u, %u), mc_xform_vertex (%d, %d, %u, %u)", k, i,
                             io.x, io.y, io.z, io.flags, o.x, o.y, o.z, o.flags);
            }
            exact e = project(&v, w, h, p);
            if (perspective && fabs(e.d - 1.0 / 64) < 1.0 / 1048576) continue;   /* on the near plane */
            if (e.near) {
                if (!(o.flags & MC_XFORM_NEAR)) fail_msg("view %d point %d: %.9f from the eye, not flagged near", k, i, e.d);
                near++;
                continue;
            }
            if (o.flags & MC_XFORM_NEAR) fail_msg("view %d point %d: flagged near at %.9f", k, i, e.d);
            if (o.z > MC_DEPTH_EMPTY - 2) fail_msg("view %d point %d: depth %u", k, i, o.z);
            if (fabs(o.z - e.z) > 1.0) fail_msg("view %d point %d: depth %u, exact %.3f", k, i, o.z, e.z);
            const double band = MC_XFORM_BAND, dx = o.x / 16.0, dy = o.y / 16.0;
            if (fabs(fabs(e.x) - band) < 1.0 / 8 || fabs(fabs(e.y) - band) < 1.0 / 8) continue;   /* on the band */
            if (e.out) {
                if (!(o.flags & MC_XFORM_FAR_OUT)) fail_msg("view %d point %d: (%.1f, %.1f) not flagged out", k, i, e.x, e.y);
                if (fabs(dx) > band || fabs(dy) > band) fail_msg("view %d point %d: not clamped to the band", k, i);
                out++;
                continue;
            }
            if (o.flags) fail_msg("view %d point %d: flags %u at (%.3f, %.3f)", k, i, o.flags, e.x, e.y);
            if (fabs(dx - e.x) > 1.0 / 16 || fabs(dy - e.y) > 1.0 / 16)
                fail_msg("view %d point %d: (%.5f, %.5f), exact (%.5f, %.5f)", k, i, dx, dy, e.x, e.y);
            if (i > 0 && !eprev.near && fabs(e.z - eprev.z) > 2 && (e.z < eprev.z) != (o.z < prev.z))
                fail_msg("view %d point %d: depth order differs from the distance's", k, i);
            prev = o, eprev = e;
            checked++;
        }
    }
    print_message("# info: %ld points within 1/16 pixel, %ld near-plane, %ld outside the band\n", checked, near, out);
    assert_true(checked > views * (long)points / 4);
    if (perspective) assert_true(near > 0 && out > 0);
}

static void test_orthographic(void **state)
{
    (void)state;
    check_views(0, 3000, 200);
}

static void test_perspective(void **state)
{
    (void)state;
    check_views(1, 3000, 200);
}

/* The frontal default view puts the cube centre on the screen centre and +y up. */
static void test_frontal(void **state)
{
    (void)state;
    mc_view v = mc_view_default();
    mc_xform x;
    mc_xform_init(&x, &v, 320, 240);
    const int32_t centre[3] = {0, 0, 0}, up[3] = {0, 16384, 0}, right[3] = {16384, 0, 0}, near[3] = {0, 0, 16384};
    mc_xvertex o, u, r, n;
    mc_xform_vertex(&x, centre, &o);
    mc_xform_vertex(&x, up, &u);
    mc_xform_vertex(&x, right, &r);
    mc_xform_vertex(&x, near, &n);
    assert_int_equal(o.x, 160 * 16);
    assert_int_equal(o.y, 120 * 16);
    assert_int_equal(u.y, (120 - 60) * 16);   /* a quarter of the cube: 240 / 4 pixels up */
    assert_int_equal(r.x, (160 + 60) * 16);
    assert_true(n.z < o.z);                  /* +z faces the viewer: nearer */
}

/* v / 2^s rounded to nearest, halves away from zero, in 128-bit integers */
static int64_t round_shift_ref(int64_t v, unsigned s)
{
    const __int128 a = v < 0 ? -(__int128)v : (__int128)v, r = (a + ((__int128)1 << (s - 1))) >> s;
    return (int64_t)(v < 0 ? -r : r);
}

static int64_t pick(mc_rng *g, unsigned s, int64_t lim)
{
    const uint64_t u = (uint64_t)mc_rng_next(g) << 32 | mc_rng_next(g);
    switch (mc_rng_next(g) % 6) {
    case 0: return (int64_t)(u % (uint64_t)lim) * (mc_rng_next(g) & 1 ? 1 : -1);           /* anywhere */
    case 1: return ((int64_t)(u % 1024) << s) + ((int64_t)1 << (s - 1)) * (mc_rng_next(g) & 1 ? 1 : -1);   /* a half */
    case 2: return -(((int64_t)(u % 1024) << s) + ((int64_t)1 << (s - 1)));                 /* a negative half */
    case 3: return (int64_t)(u % 5) - 2 + (mc_rng_next(g) & 1 ? lim - 3 : 3 - lim);          /* near the range's ends */
    case 4: return (int64_t)(u % (1u << 12)) - (1 << 11);                                    /* small */
    default: return (int64_t)(u >> (mc_rng_next(g) % 63)) * (mc_rng_next(g) & 1 ? 1 : -1);  /* any magnitude */
    }
}

static void test_round_shift(void **state)
{
    (void)state;
    mc_rng g;
    mc_rng_seed(&g, 0x5eed, 11);
    for (unsigned s = 1; s <= 62; s++)
        for (int i = 0; i < 20000; i++) {
            const int64_t lim = (int64_t)1 << 62;
            int64_t w = pick(&g, s < 50 ? s : 49, lim);
            if (w >= lim || w <= -lim) w /= 2;
            if (ortho_round_shift_small(w, s) != round_shift_ref(w, s))
                fail_msg("ortho_round_shift_small(%lld, %u) = %lld, want %lld", (long long)w, s,
                         (long long)ortho_round_shift_small(w, s), (long long)round_shift_ref(w, s));
        }
    /* the ends of the range, where a carry would leave the 64 bits */
    for (unsigned s = 1; s <= 62; s++) {
        const int64_t top = ((int64_t)1 << 62) - 1;
        assert_true(ortho_round_shift_small(top, s) == round_shift_ref(top, s));
        assert_true(ortho_round_shift_small(-top, s) == round_shift_ref(-top, s));
    }
}

/* mc_xform_box_bound: over random orthographic views and boxes (specks to the whole cube), the bounds
 * are the least and greatest of the box's corners' projections (each a monotone rounding of a linear
 * form, least or greatest at a corner), every point of the box projects inside them, and the bound is
 * refused exactly when a corner is flagged; a perspective view is always refused. */
static void test_box_bound(void **state)
{
    (void)state;
    mc_rng g;
    mc_rng_seed(&g, 0xb0c5, 5);
    long bounded = 0, refused = 0;
    for (int k = 0; k < 4000; k++) {
        const int persp = k % 10 == 9;
        mc_view v = random_view(&g, persp);
        uint32_t w = (uint32_t)rnd(&g, 1, 1024), h = (uint32_t)rnd(&g, 1, 1024);
        if (k % 4 == 1) v.zoom = 128 << 16, w = h = 4096;   /* the largest extent the clamp allows */
        mc_xform x;
        mc_xform_init(&x, &v, w, h);
        int32_t lo[3], hi[3];
        const int32_t size = rnd(&g, 0, 3) == 0 ? rnd(&g, 0, 65535) : rnd(&g, 0, 3) ? rnd(&g, 0, 64) : rnd(&g, 0, 4000);
        for (int a = 0; a < 3; a++) {
            lo[a] = rnd(&g, -32768, 32767 - (size < 65535 ? size : 65535));
            hi[a] = lo[a] + rnd(&g, 0, size);
            if (hi[a] > 32767) hi[a] = 32767;
        }
        mc_xform_box b;
        const int ok = mc_xform_box_bound(&x, lo, hi, &b);
        int32_t cx0 = INT32_MAX, cx1 = INT32_MIN, cy0 = INT32_MAX, cy1 = INT32_MIN;
        uint32_t cz0 = UINT32_MAX, flags = 0;
        for (int c = 0; c < 8; c++) {
            const int32_t p[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
            mc_xvertex e;
            mc_xform_vertex(&x, p, &e);
            flags |= e.flags;
            cx0 = e.x < cx0 ? e.x : cx0, cx1 = e.x > cx1 ? e.x : cx1, cy0 = e.y < cy0 ? e.y : cy0, cy1 = e.y > cy1 ? e.y : cy1;
            cz0 = e.z < cz0 ? e.z : cz0;
        }
        if (persp) {
            assert_int_equal(ok, 0);
            continue;
        }
        if (ok != !flags) fail_msg("view %d: bound %s with corners' flags %u", k, ok ? "taken" : "refused", (unsigned)flags);
        if (!ok) {
            refused++;
            continue;
        }
        bounded++;
        if (b.x0 != cx0 || b.x1 != cx1 || b.y0 != cy0 || b.y1 != cy1 || b.z0 != cz0)
            fail_msg("view %d: bound x %d..%d y %d..%d z >= %u, the corners x %d..%d y %d..%d z >= %u", k, b.x0, b.x1, b.y0,
                     b.y1, (unsigned)b.z0, cx0, cx1, cy0, cy1, (unsigned)cz0);
        for (int i = 0; i < 40; i++) {
            int32_t p[3];
            for (int a = 0; a < 3; a++) p[a] = rnd(&g, lo[a], hi[a]);
            mc_xvertex e;
            mc_xform_vertex(&x, p, &e);
            if (e.flags || e.x < b.x0 || e.x > b.x1 || e.y < b.y0 || e.y > b.y1 || e.z < b.z0)
                fail_msg("view %d: point (%d %d %d) at (%d %d %u) flags %u, outside its box's bound", k, p[0], p[1], p[2], e.x,
                         e.y, (unsigned)e.z, (unsigned)e.flags);
        }
    }
    /* both outcomes met often */
    /* (mc_view_clamp keeps the cube within the band in an orthographic view: a refusal there is never
     * met, and checked all the same whenever a corner is flagged) */
    assert_true(bounded > 3000);
    print_message("# info: %ld boxes bounded, %ld refused (a corner beyond the band)\n", bounded, refused);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_shift),
        cmocka_unit_test(test_frontal),
        cmocka_unit_test(test_orthographic),
        cmocka_unit_test(test_perspective),
        cmocka_unit_test(test_box_bound),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
