/* Sine, cosine and the view rotation (modelc/trig.h, runtime/src/trig.c, sintab.c, xform.c).
 *
 * References are long double: sinl(2 pi a / 4096) with the angle first reduced exactly to a turn in
 * integers, so the reference itself is good to ~1e-9 units of Q30; every bound below adds a slack of
 * 1e-6 units for it.
 *
 * Bounds (u = one unit of Q30 = 2^-30):
 *   mc_sin, mc_cos:      |result - 2^30 sin| <= 0.5 u          (the table is rounded to nearest)
 *   sin^2 + cos^2:       |s^2 + c^2 - 1| <= sqrt(2) u + 0.5 u^2 (from the two 0.5 u errors)
 *   mc_view_rotation:    each entry within 4 u of the exact Rz(roll) Rx(pitch) Ry(yaw) computed from the
 *                        exact sines, and within 1.25 u of the same product of the runtime's own Q30
 *                        sines. Derivation: T = Rx*Ry is rounded once (0.5 u) and each entry carries two
 *                        inexact factors per row and column, 0.5 u each, weighted by unit vectors
 *                        (<= 0.5 u sqrt 2 for each matrix): <= 0.5 + sqrt 2 = 1.92 u. Rz*T adds 0.5 u of
 *                        rounding, 0.5 u sqrt 2 from Rz and carries T's error through a row of Rz
 *                        (sum of |entries| <= sqrt 2): <= 0.5 + 0.71 + 2.71 = 3.92 u. From the Q30 sines
 *                        the factor errors vanish and only the roundings remain: 0.5 + 0.5 sqrt 2 = 1.21 u.
 *                        So R = R_exact + E with |E_ij| <= 3.92 u: |R R^T - I| <= 2 sqrt 3 * 3.92 = 13.6 u
 *                        -> bound 14 u; |det R - 1| <= |E|_F |R|_F <= 3 * 3.92 * sqrt 3 = 20.4 u -> bound
 *                        21 u (and det near +1 means a rotation, not a reflection).
 */
#include <inttypes.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include <modelc/trig.h>
#include <modelc/xform.h>

#define PI_L 3.14159265358979323846264338327950288L
#define Q30 1073741824.0L
#define SLACK 1e-6L

static uint64_t rng_state = 11;
static uint64_t rng64(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

/* exact reduction modulo a turn, then sinl of a small argument */
static long double ref_sin(int64_t angle)
{
    int64_t a = angle % 4096;
    if (a < 0) a += 4096;
    return sinl(2 * PI_L * (long double)a / 4096.0L);
}
static long double ref_cos(int64_t angle) { return ref_sin(angle + 1024); }

static void check_angle(int32_t a, long double *worst)
{
    long double es = (long double)mc_sin(a) - ref_sin(a) * Q30;
    long double ec = (long double)mc_cos(a) - ref_cos(a) * Q30;
    if (fabsl(es) > 0.5L + SLACK)
        fail_msg("mc_sin(%" PRId32 ") = %" PRId32 " is %.6Lf units of Q30 from 2^30 sin(2 pi a/4096)"
                 " (bound 0.5 + 1e-6)", a, mc_sin(a), es);
    if (fabsl(ec) > 0.5L + SLACK)
        fail_msg("mc_cos(%" PRId32 ") = %" PRId32 " is %.6Lf units of Q30 from 2^30 cos(2 pi a/4096)"
                 " (bound 0.5 + 1e-6)", a, mc_cos(a), ec);
    if (worst) {
        if (fabsl(es) > *worst) *worst = fabsl(es);
        if (fabsl(ec) > *worst) *worst = fabsl(ec);
    }
}

static void test_every_angle(void **state)
{
    (void)state;
    long double worst = 0;
    for (int32_t a = 0; a < 4096; a++) check_angle(a, &worst);
    for (int32_t a = -4096; a < 0; a++) check_angle(a, &worst);
    print_message("# info: max |error| over every angle: %.4Lf units of Q30 (bound 0.5)\n", worst);
    /* exact values at the quarter turns */
    assert_int_equal(mc_sin(0), 0);
    assert_int_equal(mc_sin(1024), MC_TRIG_ONE);
    assert_int_equal(mc_sin(2048), 0);
    assert_int_equal(mc_sin(3072), -MC_TRIG_ONE);
    assert_int_equal(mc_cos(0), MC_TRIG_ONE);
    assert_int_equal(mc_cos(1024), 0);
    assert_int_equal(mc_cos(2048), -MC_TRIG_ONE);
    assert_int_equal(mc_cos(3072), 0);
}

static void test_symmetry(void **state)
{
    (void)state;
    for (int32_t a = -8192; a <= 8192; a++) {
        /* odd sine, even cosine, cos(a) = sin(a + quarter), sin(a + half) = -sin(a): exactly */
        if (mc_sin(-a) != -mc_sin(a)) fail_msg("mc_sin(-%" PRId32 ") != -mc_sin(%" PRId32 ")", a, a);
        if (mc_cos(-a) != mc_cos(a)) fail_msg("mc_cos(-%" PRId32 ") != mc_cos(%" PRId32 ")", a, a);
        if (mc_cos(a) != mc_sin(a + 1024)) fail_msg("mc_cos(%" PRId32 ") != mc_sin(a + 1024)", a);
        if (mc_sin(a + 2048) != -mc_sin(a)) fail_msg("mc_sin(%" PRId32 " + 2048) != -mc_sin(a)", a);
        if (mc_sin(2048 - a) != mc_sin(a)) fail_msg("mc_sin(2048 - %" PRId32 ") != mc_sin(a)", a);
        /* |s^2 + c^2 - 1| <= sqrt(2) u + 0.5 u^2, in units of 2^-60: sqrt(2) * 2^30 + 0.5 */
        int64_t s = mc_sin(a), c = mc_cos(a);
        int64_t e = s * s + c * c - ((int64_t)1 << 60);
        if ((e < 0 ? -e : e) > (int64_t)(1.41421357 * 1073741824.0) + 1)
            fail_msg("sin^2 + cos^2 of %" PRId32 " is 1 + %" PRId64 " * 2^-60 (bound sqrt(2) * 2^-30)", a, e);
    }
    /* the quarter-wave table rises monotonically */
    for (int32_t a = 0; a < 1024; a++)
        if (mc_sin(a + 1) <= mc_sin(a)) fail_msg("mc_sin not increasing at %" PRId32, a);
}

static void test_wrapping(void **state)
{
    (void)state;
    /* any int32 is taken modulo a turn */
    static const int32_t special[] = {INT32_MIN, INT32_MIN + 1, INT32_MIN + 1023, INT32_MIN + 1024,
                                      INT32_MIN + 4095, -4097, -4096, -1, 4096, 4097, 1 << 30,
                                      INT32_MAX - 4096, INT32_MAX - 1024, INT32_MAX - 1, INT32_MAX};
    for (size_t i = 0; i < sizeof special / sizeof special[0]; i++) check_angle(special[i], NULL);
    assert_int_equal(mc_sin(INT32_MIN), 0);              /* -2^31 = -524288 turns */
    assert_int_equal(mc_cos(INT32_MIN), MC_TRIG_ONE);
    assert_int_equal(mc_sin(INT32_MAX), mc_sin(4095));
    assert_int_equal(mc_cos(INT32_MAX), mc_cos(4095));
    assert_int_equal(mc_cos(INT32_MAX - 1023), mc_cos(3072));
    for (int i = 0; i < 1000000; i++) {
        int32_t a = (int32_t)(uint32_t)rng64();
        int32_t r = (int32_t)(((int64_t)a % 4096 + 4096) % 4096);
        if (mc_sin(a) != mc_sin(r) || mc_cos(a) != mc_cos(r))
            fail_msg("angle %" PRId32 " does not give the same sine/cosine as %" PRId32 " (modulo a turn)", a, r);
    }
}

/* ---- rotation ------------------------------------------------------------------------------ */

typedef long double mat[3][3];

static void matmul_l(mat a, mat b, mat out)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            long double s = 0;
            for (int k = 0; k < 3; k++) s += a[i][k] * b[k][j];
            out[i][j] = s;
        }
}

/* Rz(roll) Rx(pitch) Ry(yaw) from the given sines and cosines (in units of 1) */
static void ref_rotation(long double sy, long double cy, long double sp, long double cp, long double sr,
                         long double cr, mat out)
{
    mat ry = {{cy, 0, sy}, {0, 1, 0}, {-sy, 0, cy}};
    mat rx = {{1, 0, 0}, {0, cp, -sp}, {0, sp, cp}};
    mat rz = {{cr, -sr, 0}, {sr, cr, 0}, {0, 0, 1}};
    mat t;
    matmul_l(rx, ry, t);
    matmul_l(rz, t, out);
}

static int32_t rand_angle(void)
{
    switch (rng64() % 4) {
    case 0: return (int32_t)(uint32_t)rng64();                          /* any int32 */
    case 1: return (int32_t)(rng64() % 8192) - 4096;                    /* about one turn */
    case 2: return (int32_t)(rng64() % 16) * 256 + (int32_t)(rng64() % 3) - 1;  /* near multiples of 1/16 */
    default: {
        static const int32_t e[] = {INT32_MIN, INT32_MAX, 0, 1024, 2048, 3072, -1024};
        return e[rng64() % (sizeof e / sizeof e[0])];
    }
    }
}

static void test_rotation(void **state)
{
    (void)state;
    long double worst_exact = 0, worst_q = 0, worst_orth = 0, worst_det = 0;
    for (int n = 0; n < 300000; n++) {
        mc_view v = mc_view_default();
        v.yaw = rand_angle();
        v.pitch = rand_angle();
        v.roll = rand_angle();
        int32_t r[3][3];
        mc_view_rotation(&v, r);
        mat exact, fromq;
        ref_rotation(ref_sin(v.yaw), ref_cos(v.yaw), ref_sin(v.pitch), ref_cos(v.pitch), ref_sin(v.roll),
                     ref_cos(v.roll), exact);
        ref_rotation(mc_sin(v.yaw) / Q30, mc_cos(v.yaw) / Q30, mc_sin(v.pitch) / Q30, mc_cos(v.pitch) / Q30,
                     mc_sin(v.roll) / Q30, mc_cos(v.roll) / Q30, fromq);
        mat rl;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                rl[i][j] = r[i][j] / Q30;
                long double e1 = fabsl(r[i][j] - exact[i][j] * Q30), e2 = fabsl(r[i][j] - fromq[i][j] * Q30);
                if (e1 > worst_exact) worst_exact = e1;
                if (e2 > worst_q) worst_q = e2;
                if (e1 > 4.0L + SLACK)
                    fail_msg("rotation(yaw %" PRId32 ", pitch %" PRId32 ", roll %" PRId32 ")[%d][%d] = %" PRId32
                             " is %.3Lf units of Q30 from Rz*Rx*Ry (bound 4)", v.yaw, v.pitch, v.roll, i, j,
                             r[i][j], e1);
                if (e2 > 1.25L + SLACK)
                    fail_msg("rotation(yaw %" PRId32 ", pitch %" PRId32 ", roll %" PRId32 ")[%d][%d] = %" PRId32
                             " is %.3Lf units of Q30 from Rz*Rx*Ry of the runtime's own sines (bound 1.25)",
                             v.yaw, v.pitch, v.roll, i, j, r[i][j], e2);
            }
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                long double dot = 0;
                for (int k = 0; k < 3; k++) dot += rl[i][k] * rl[j][k];
                long double e = fabsl(dot - (i == j)) * Q30;
                if (e > worst_orth) worst_orth = e;
                if (e > 14.0L)
                    fail_msg("rotation(yaw %" PRId32 ", pitch %" PRId32 ", roll %" PRId32 "): (R R^T)[%d][%d]"
                             " is %.3Lf units of Q30 from the identity (bound 14)", v.yaw, v.pitch, v.roll, i,
                             j, e);
            }
        long double det = rl[0][0] * (rl[1][1] * rl[2][2] - rl[1][2] * rl[2][1]) -
                          rl[0][1] * (rl[1][0] * rl[2][2] - rl[1][2] * rl[2][0]) +
                          rl[0][2] * (rl[1][0] * rl[2][1] - rl[1][1] * rl[2][0]);
        long double ed = fabsl(det - 1) * Q30;
        if (ed > worst_det) worst_det = ed;
        if (ed > 21.0L)
            fail_msg("rotation(yaw %" PRId32 ", pitch %" PRId32 ", roll %" PRId32 "): det = 1 %+.3Lf units of Q30"
                     " (bound 21)", v.yaw, v.pitch, v.roll, (det - 1) * Q30);
    }
    print_message("# info: rotation: max entry error %.3Lf u vs exact (bound 4), %.3Lf u vs own sines (bound 1.25),"
                  " |R R^T - I| %.3Lf u (bound 14), |det - 1| %.3Lf u (bound 21)\n",
                  worst_exact, worst_q, worst_orth, worst_det);
    /* the identity at zero angles, exactly */
    mc_view v = mc_view_default();
    int32_t r[3][3];
    mc_view_rotation(&v, r);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) assert_int_equal(r[i][j], i == j ? MC_TRIG_ONE : 0);
    /* a quarter turn of yaw maps the model's +z (towards the viewer) to +x: R e_z = e_x, R e_x = -e_z */
    v.yaw = 1024;
    mc_view_rotation(&v, r);
    assert_int_equal(r[0][2], MC_TRIG_ONE);
    assert_int_equal(r[2][0], -MC_TRIG_ONE);
    assert_int_equal(r[1][1], MC_TRIG_ONE);
}

int main(void)
{
    setvbuf(stdout, NULL, _IONBF, 0);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_angle),
        cmocka_unit_test(test_symmetry),
        cmocka_unit_test(test_wrapping),
        cmocka_unit_test(test_rotation),
    };
    return cmocka_run_group_tests_name("trig", tests, NULL, NULL);
}
