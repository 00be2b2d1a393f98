/* Fixed-point arithmetic (modelc/fixed.h, runtime/src/fixed.c) against exact references.
 *
 * Every operation promises: round to nearest, ties away from zero, and saturate at MC_FIX_MIN /
 * MC_FIX_MAX (INT64_MIN / INT64_MAX for mc_mul_shift64) instead of wrapping. So the expected result of
 * each operation is computed exactly (__int128 / long double on the host, independently of the
 * runtime's formulas) and the result must be EQUAL to it: an error bound of 0.5 ulp of the exact
 * value, with ties going away from zero, unless the exact value lies outside the range, in which case
 * the result must be the end of the range on the side of the exact value (never a wrapped value).
 * The long double cross-checks state the same bound in real numbers (|result - exact| <= 0.5 ulp).
 *
 * Operands: every pair from an edge list (range ends, 0, +-1, +-one, powers of two and their
 * neighbours) plus 10^6 random operands per operation from a fixed seed, drawn uniformly over the full
 * range, log-uniformly in magnitude (so small values and values near each power of two are hit), and
 * near the range ends. Built once per MC_FRAC_BITS the suite asks for (8, 15, 24).
 */
#include <float.h>
#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include <modelc/fixed.h>

#define F MC_FRAC_BITS
#define RANDOM_N 1000000

typedef __int128 i128;
typedef unsigned __int128 u128;

/* ---- deterministic operands ---------------------------------------------------------------- */

static uint64_t rng_state;
static void rng_seed(uint64_t s) { rng_state = s; }
static uint64_t rng64(void) /* splitmix64 */
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

/* Random int64: a third uniform, a third log-uniform magnitude with random sign, a third within 64 of
 * an end of the range or of zero. */
static int64_t rand_i64(void)
{
    uint64_t sel = rng64() % 3, r = rng64();
    if (sel == 0) return (int64_t)r;
    if (sel == 1) {
        int bits = (int)(rng64() % 64);           /* magnitude below 2^bits */
        uint64_t m = bits ? r >> (64 - bits) : 0;
        return (rng64() & 1) ? -(int64_t)m : (int64_t)m;
    }
    int64_t off = (int64_t)(r % 64);
    switch (rng64() % 3) {
    case 0: return INT64_MIN + off;
    case 1: return INT64_MAX - off;
    default: return off - 32;
    }
}

static int32_t rand_i32(void)
{
    uint64_t sel = rng64() % 3, r = rng64();
    if (sel == 0) return (int32_t)(uint32_t)r;
    if (sel == 1) {
        int bits = (int)(rng64() % 32);
        int32_t m = bits ? (int32_t)((uint32_t)r >> (32 - bits)) : 0;
        return (rng64() & 1) ? -m : m;
    }
    int32_t off = (int32_t)(r % 64);
    switch (rng64() % 3) {
    case 0: return INT32_MIN + off;
    case 1: return INT32_MAX - off;
    default: return off - 32;
    }
}

static const int32_t edges32[] = {
    INT32_MIN, INT32_MIN + 1, INT32_MIN / 2, -(1 << 30) - 1, -MC_FIX_ONE - 1, -MC_FIX_ONE,
    -MC_FIX_ONE + 1, -(MC_FIX_ONE / 2) - 1, -(MC_FIX_ONE / 2), -3, -2, -1, 0, 1, 2, 3, MC_FIX_ONE / 2,
    MC_FIX_ONE / 2 + 1, MC_FIX_ONE - 1, MC_FIX_ONE, MC_FIX_ONE + 1, 3 * MC_FIX_ONE, 46341, 1 << 30,
    INT32_MAX / 2, INT32_MAX - 1, INT32_MAX};
#define N_EDGES32 (sizeof edges32 / sizeof edges32[0])

static const int64_t edges64[] = {
    INT64_MIN, INT64_MIN + 1, INT64_MIN / 2, -((int64_t)1 << 62) - 1, -((int64_t)1 << 32) - 1,
    -((int64_t)1 << 32), -(int64_t)UINT32_MAX, INT32_MIN, -((int64_t)1 << 30), -3, -2, -1, 0, 1, 2, 3,
    (int64_t)1 << 30, INT32_MAX, (int64_t)UINT32_MAX, (int64_t)1 << 32, ((int64_t)1 << 32) + 1,
    (int64_t)1 << 62, ((int64_t)1 << 62) + 1, INT64_MAX / 3, INT64_MAX - 1, INT64_MAX};
#define N_EDGES64 (sizeof edges64 / sizeof edges64[0])

/* ---- exact references ---------------------------------------------------------------------- */

/* x / 2^s rounded to nearest, ties away from zero, exactly (any x with |x| < 2^126, s 0..126). */
static i128 ref_round_shift(i128 x, int s)
{
    if (s == 0) return x;
    u128 m = x < 0 ? (u128)0 - (u128)x : (u128)x;
    u128 q = m >> s, rem = m - (q << s), half = (u128)1 << (s - 1);
    if (rem >= half) q++;                    /* rem == half is a tie: away from zero */
    return x < 0 ? -(i128)q : (i128)q;
}

/* n / d rounded to nearest, ties away from zero (d != 0). */
static i128 ref_round_div(i128 n, i128 d)
{
    i128 q = n / d, r = n % d;               /* truncated toward zero, |r| < |d| */
    i128 ar = r < 0 ? -r : r, ad = d < 0 ? -d : d;
    if (2 * ar >= ad) q += ((n < 0) != (d < 0)) ? -1 : 1;
    return q;
}

static int32_t sat32(i128 v) { return v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (int32_t)v; }
static int64_t sat64(i128 v) { return v > INT64_MAX ? INT64_MAX : v < INT64_MIN ? INT64_MIN : (int64_t)v; }

static const char *i128s(i128 v, char *buf) /* for messages */
{
    char tmp[48];
    int n = 0, neg = v < 0;
    u128 m = neg ? (u128)0 - (u128)v : (u128)v;
    do { tmp[n++] = (char)('0' + (int)(m % 10)); m /= 10; } while (m);
    int k = 0;
    if (neg) buf[k++] = '-';
    while (n) buf[k++] = tmp[--n];
    buf[k] = 0;
    return buf;
}

/* ---- checks -------------------------------------------------------------------------------- */

static void check_mul(int32_t a, int32_t b)
{
    int64_t p = (int64_t)a * b;                      /* exact: |p| <= 2^62 */
    int32_t want = sat32(ref_round_shift(p, F));
    int32_t got = mc_fix_mul(a, b);
    if (got != want)
        fail_msg("mc_fix_mul(%" PRId32 ", %" PRId32 ") = %" PRId32 ", want %" PRId32
                 " (bound: exactly rounded, <= 0.5 ulp of a*b/2^%d, ties away from zero, saturated)",
                 a, b, got, want, F);
#if LDBL_MANT_DIG >= 64
    /* the same bound in real numbers: the long double product of two int32 is exact */
    long double exact = (long double)a * (long double)b / (long double)MC_FIX_ONE;
    long double err = (long double)got - exact;
    if (got != INT32_MAX && got != INT32_MIN && (err > 0.5L || err < -0.5L))
        fail_msg("mc_fix_mul(%" PRId32 ", %" PRId32 ") = %" PRId32 " is %.3Lf ulp from the exact product"
                 " (bound 0.5 ulp unless saturated)", a, b, got, err);
    if ((got == INT32_MAX && exact < INT32_MAX - 0.5L) || (got == INT32_MIN && exact > INT32_MIN + 0.5L))
        fail_msg("mc_fix_mul(%" PRId32 ", %" PRId32 ") saturated to %" PRId32 " but the exact product %.3Lf"
                 " is representable", a, b, got, exact);
#endif
}

static void check_div(int32_t a, int32_t b)
{
    int32_t got = mc_fix_div(a, b);
    int32_t want;
    if (b == 0) want = a > 0 ? MC_FIX_MAX : a < 0 ? MC_FIX_MIN : 0;
    else want = sat32(ref_round_div((i128)a * MC_FIX_ONE, b));
    if (got != want)
        fail_msg("mc_fix_div(%" PRId32 ", %" PRId32 ") = %" PRId32 ", want %" PRId32
                 " (bound: exactly rounded, <= 0.5 ulp of (a/b), ties away from zero, saturated;"
                 " x/0 = MAX, MIN or 0 by the sign of x)", a, b, got, want);
#if LDBL_MANT_DIG >= 64
    if (b != 0 && got != INT32_MAX && got != INT32_MIN) {
        long double exact = (long double)a * MC_FIX_ONE / (long double)b;    /* a*2^F exact; one rounding */
        long double err = (long double)got - exact;
        if (err > 0.5L + 1e-9L || err < -0.5L - 1e-9L)
            fail_msg("mc_fix_div(%" PRId32 ", %" PRId32 ") = %" PRId32 " is %.6Lf ulp from a/b"
                     " (bound 0.5 ulp + 1e-9 long double slack)", a, b, got, err);
    }
#endif
}

static void check_add_sub(int32_t a, int32_t b)
{
    int32_t got = mc_fix_add(a, b), want = sat32((i128)a + b);
    if (got != want)
        fail_msg("mc_fix_add(%" PRId32 ", %" PRId32 ") = %" PRId32 ", want %" PRId32 " (exact, saturated)", a, b,
                 got, want);
    got = mc_fix_sub(a, b);
    want = sat32((i128)a - b);
    if (got != want)
        fail_msg("mc_fix_sub(%" PRId32 ", %" PRId32 ") = %" PRId32 ", want %" PRId32 " (exact, saturated)", a, b,
                 got, want);
}

static void check_from_int_floor(int32_t i)
{
    int32_t got = mc_fix_from_int(i), want = sat32((i128)i * MC_FIX_ONE);
    if (got != want)
        fail_msg("mc_fix_from_int(%" PRId32 ") = %" PRId32 ", want %" PRId32 " (exact, saturated)", i, got, want);
    /* floor: the largest n with n * 2^F <= i */
    int64_t fl = (int64_t)i >= 0 ? (int64_t)i / MC_FIX_ONE : -((-(int64_t)i + MC_FIX_ONE - 1) / MC_FIX_ONE);
    if (mc_fix_floor(i) != fl)
        fail_msg("mc_fix_floor(%" PRId32 ") = %" PRId32 ", want %" PRId64 " (round toward minus infinity)", i,
                 mc_fix_floor(i), fl);
}

static void check_round_shift(int64_t v, int s)
{
    int64_t got = mc_round_shift(v, s);
    int64_t want = (int64_t)ref_round_shift(v, s);
    if (got != want) {
        char b1[48];
        fail_msg("mc_round_shift(%" PRId64 ", %d) = %" PRId64 ", want %s"
                 " (bound: exactly rounded to nearest, ties away from zero; s in 0..63, v > INT64_MIN)",
                 v, s, got, i128s(want, b1));
    }
}

static void check_mul_shift64(int64_t a, int64_t b, int s)
{
    int64_t got = mc_mul_shift64(a, b, s);
    int64_t want = sat64(ref_round_shift((i128)a * b, s));
    if (got != want) {
        char b1[48];
        fail_msg("mc_mul_shift64(%" PRId64 ", %" PRId64 ", %d) = %" PRId64 ", want %s"
                 " (bound: exact 128-bit product, rounded once to nearest, ties away from zero,"
                 " saturated to int64)", a, b, s, got, i128s(want, b1));
    }
}

/* ---- tests --------------------------------------------------------------------------------- */

static void test_sat(void **state)
{
    (void)state;
    static const int64_t v[] = {INT64_MIN, (int64_t)INT32_MIN - 1, INT32_MIN, INT32_MIN + 1, -1, 0, 1,
                                INT32_MAX - 1, INT32_MAX, (int64_t)INT32_MAX + 1, INT64_MAX};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        assert_int_equal(mc_fix_sat(v[i]), sat32(v[i]));
    rng_seed(1);
    for (int i = 0; i < RANDOM_N; i++) {
        int64_t x = rand_i64();
        if (mc_fix_sat(x) != sat32(x))
            fail_msg("mc_fix_sat(%" PRId64 ") = %" PRId32 " (want the clamp to int32)", x, mc_fix_sat(x));
    }
}

static void test_from_int_floor(void **state)
{
    (void)state;
    for (size_t i = 0; i < N_EDGES32; i++) check_from_int_floor(edges32[i]);
    /* the representable integer range ends exactly at +-2^(31-F) */
    int32_t lim = (int32_t)1 << (31 - F);
    for (int32_t i = -lim - 2; i <= -lim + 2; i++) check_from_int_floor(i);
    for (int32_t i = lim - 2; i <= lim + 2; i++) check_from_int_floor(i);
    assert_int_equal(mc_fix_from_int(lim), MC_FIX_MAX);
    assert_int_equal(mc_fix_from_int(-lim), MC_FIX_MIN);   /* exactly representable */
    assert_int_equal(mc_fix_from_int(INT32_MIN), MC_FIX_MIN);
    rng_seed(2);
    for (int i = 0; i < RANDOM_N; i++) check_from_int_floor(rand_i32());
}

static void test_add_sub(void **state)
{
    (void)state;
    for (size_t i = 0; i < N_EDGES32; i++)
        for (size_t j = 0; j < N_EDGES32; j++) check_add_sub(edges32[i], edges32[j]);
    /* saturation, never wrapping */
    assert_int_equal(mc_fix_add(INT32_MAX, 1), INT32_MAX);
    assert_int_equal(mc_fix_add(INT32_MIN, -1), INT32_MIN);
    assert_int_equal(mc_fix_sub(INT32_MIN, 1), INT32_MIN);
    assert_int_equal(mc_fix_sub(0, INT32_MIN), INT32_MAX);
    assert_int_equal(mc_fix_sub(-1, INT32_MIN), INT32_MAX);
    rng_seed(3);
    for (int i = 0; i < RANDOM_N; i++) check_add_sub(rand_i32(), rand_i32());
}

static void test_mul(void **state)
{
    (void)state;
    for (size_t i = 0; i < N_EDGES32; i++)
        for (size_t j = 0; j < N_EDGES32; j++) check_mul(edges32[i], edges32[j]);
    /* rounding mode: exact half-ulp products go away from zero, others to nearest */
    const int32_t half = MC_FIX_ONE / 2;
    assert_int_equal(mc_fix_mul(1, half), 1);             /* 0.5 ulp  -> 1 */
    assert_int_equal(mc_fix_mul(-1, half), -1);           /* -0.5 ulp -> -1 */
    assert_int_equal(mc_fix_mul(1, -half), -1);
    assert_int_equal(mc_fix_mul(3, half), 2);             /* 1.5 ulp  -> 2 */
    assert_int_equal(mc_fix_mul(-3, half), -2);
    assert_int_equal(mc_fix_mul(1, half - 1), 0);         /* just under half -> 0 */
    assert_int_equal(mc_fix_mul(-1, half - 1), 0);
    assert_int_equal(mc_fix_mul(1, half + 1), 1);
    /* one is the identity; saturation keeps the sign of the exact product */
    assert_int_equal(mc_fix_mul(INT32_MIN, MC_FIX_ONE), INT32_MIN);
    assert_int_equal(mc_fix_mul(INT32_MAX, MC_FIX_ONE), INT32_MAX);
    assert_int_equal(mc_fix_mul(INT32_MIN, -MC_FIX_ONE), INT32_MAX);   /* -MIN: not representable */
    assert_int_equal(mc_fix_mul(INT32_MIN, INT32_MIN), INT32_MAX);
    assert_int_equal(mc_fix_mul(INT32_MIN, INT32_MAX), INT32_MIN);
    assert_int_equal(mc_fix_mul(INT32_MAX, INT32_MAX), INT32_MAX);
    rng_seed(4);
    for (int i = 0; i < RANDOM_N; i++) check_mul(rand_i32(), rand_i32());
}

static void test_div(void **state)
{
    (void)state;
    for (size_t i = 0; i < N_EDGES32; i++)
        for (size_t j = 0; j < N_EDGES32; j++) check_div(edges32[i], edges32[j]);
    /* division by zero saturates toward the sign of the dividend; 0/0 = 0 */
    assert_int_equal(mc_fix_div(1, 0), MC_FIX_MAX);
    assert_int_equal(mc_fix_div(INT32_MAX, 0), MC_FIX_MAX);
    assert_int_equal(mc_fix_div(-1, 0), MC_FIX_MIN);
    assert_int_equal(mc_fix_div(INT32_MIN, 0), MC_FIX_MIN);
    assert_int_equal(mc_fix_div(0, 0), 0);
    /* rounding mode: 1 ulp / 2 = 0.5 ulp -> 1; -> -1 for negative quotients */
    assert_int_equal(mc_fix_div(1, 2 * MC_FIX_ONE), 1);
    assert_int_equal(mc_fix_div(-1, 2 * MC_FIX_ONE), -1);
    assert_int_equal(mc_fix_div(1, -2 * MC_FIX_ONE), -1);
    assert_int_equal(mc_fix_div(3, 2 * MC_FIX_ONE), 2);
    assert_int_equal(mc_fix_div(-3, -2 * MC_FIX_ONE), 2);
    assert_int_equal(mc_fix_div(1, 3 * MC_FIX_ONE), 0);   /* 1/3 ulp -> 0 */
    assert_int_equal(mc_fix_div(2, 3 * MC_FIX_ONE), 1);   /* 2/3 ulp -> 1 */
    /* saturation, never wrapping */
    assert_int_equal(mc_fix_div(INT32_MIN, -MC_FIX_ONE), INT32_MAX);
    assert_int_equal(mc_fix_div(INT32_MIN, -1), INT32_MAX);
    assert_int_equal(mc_fix_div(INT32_MAX, 1), INT32_MAX);
    assert_int_equal(mc_fix_div(INT32_MIN, 1), INT32_MIN);
    assert_int_equal(mc_fix_div(INT32_MIN, INT32_MIN), MC_FIX_ONE);
    rng_seed(5);
    for (int i = 0; i < RANDOM_N; i++) check_div(rand_i32(), rand_i32());
    /* divisors of every magnitude with dividends of every magnitude */
    for (int i = 0; i < RANDOM_N / 4; i++) {
        int32_t a = rand_i32(), b = (int32_t)(rng64() % 4096) - 2048;
        check_div(a, b);
    }
    for (int32_t a = -600; a <= 600; a++) check_div(a, 0);
}

/* mc_round_shift over its documented domain, v in (INT64_MIN, INT64_MAX], s in 0..63, except the
 * values within 2^(s-1) of the int64 ends (test_round_shift_extremes, kept separate so a failure
 * there names itself and, under UBSan, stops the binary only after everything else ran) */
static int near_end(int64_t v, int s)
{
    if (s == 0) return 0;
    int64_t half = (int64_t)1 << (s - 1);
    return v > INT64_MAX - half || v < INT64_MIN + 1 + half;
}

static void test_round_shift(void **state)
{
    (void)state;
    for (int s = 0; s <= 63; s++) {
        for (size_t i = 0; i < N_EDGES64; i++)
            if (edges64[i] != INT64_MIN && !near_end(edges64[i], s)) check_round_shift(edges64[i], s);
        /* ties and their neighbours at this shift: (2k+1) * 2^(s-1) +- 1 */
        if (s > 0) {
            for (int k = -4; k <= 4; k++) {
                for (int d = -1; d <= 1; d++) {
                    i128 t = (i128)(2 * k + 1) * ((i128)1 << (s - 1)) + d;
                    if (t <= INT64_MIN || t > INT64_MAX || near_end((int64_t)t, s)) continue;
                    check_round_shift((int64_t)t, s);
                }
            }
        }
    }
    assert_int_equal(mc_round_shift(5, 1), 3);     /* 2.5 -> 3 */
    assert_int_equal(mc_round_shift(-5, 1), -3);   /* -2.5 -> -3 */
    assert_int_equal(mc_round_shift(3, 2), 1);     /* 0.75 -> 1 */
    assert_int_equal(mc_round_shift(-2, 2), -1);   /* -0.5 -> -1 */
    assert_int_equal(mc_round_shift(-1, 2), 0);    /* -0.25 -> 0 */
    rng_seed(6);
    for (int i = 0; i < RANDOM_N; i++) {
        int64_t v = rand_i64();
        int s = (int)(rng64() % 64);
        if (v == INT64_MIN || near_end(v, s)) continue;
        check_round_shift(v, s);
    }
}

static void test_round_shift_extremes(void **state)
{
    (void)state;
    /* still inside the documented domain (s 0..63, v > INT64_MIN): the largest magnitudes. The exact
     * results are all representable (|v| / 2 rounded), so there is nothing to saturate. */
    for (int s = 1; s <= 63; s++) {
        check_round_shift(INT64_MAX, s);
        check_round_shift(INT64_MAX - 1, s);
        check_round_shift(INT64_MIN + 1, s);
        check_round_shift(INT64_MIN + 2, s);
    }
}

static void test_mul_shift64(void **state)
{
    (void)state;
    for (int s = 0; s <= 126; s++)
        for (size_t i = 0; i < N_EDGES64; i++)
            for (size_t j = 0; j < N_EDGES64; j++) check_mul_shift64(edges64[i], edges64[j], s);
    /* rounding and saturation by hand */
    assert_true(mc_mul_shift64(3, 1, 1) == 2);                    /* 1.5 -> 2 */
    assert_true(mc_mul_shift64(-3, 1, 1) == -2);                  /* -1.5 -> -2 */
    assert_true(mc_mul_shift64(5, 1, 2) == 1);                    /* 1.25 -> 1 */
    assert_true(mc_mul_shift64(1, 1, 126) == 0);
    assert_true(mc_mul_shift64(INT64_MIN, INT64_MIN, 126) == 1);  /* 2^126 / 2^126 */
    assert_true(mc_mul_shift64(INT64_MIN, INT64_MAX, 126) == -1); /* -(2^126 - 2^63) / 2^126 -> -1 */
    assert_true(mc_mul_shift64(INT64_MIN, INT64_MIN, 0) == INT64_MAX);
    assert_true(mc_mul_shift64(INT64_MIN, 1, 0) == INT64_MIN);    /* exact, not saturated */
    assert_true(mc_mul_shift64(INT64_MIN, -1, 0) == INT64_MAX);   /* 2^63: saturated, not wrapped */
    assert_true(mc_mul_shift64(INT64_MAX, INT64_MAX, 62) == INT64_MAX);
    assert_true(mc_mul_shift64(INT64_MAX, INT64_MAX, 63) == INT64_MAX - 1 + 0); /* (2^63-1)^2/2^63 = 2^63-2+2^-63 */
    assert_true(mc_mul_shift64((int64_t)1 << 32, (int64_t)1 << 32, 64) == 1);
    assert_true(mc_mul_shift64((int64_t)1 << 32, ((int64_t)1 << 31), 64) == 1);  /* 0.5 -> 1 */
    assert_true(mc_mul_shift64(-((int64_t)1 << 32), ((int64_t)1 << 31), 64) == -1);
    rng_seed(7);
    for (int i = 0; i < RANDOM_N; i++) {
        int64_t a = rand_i64(), b = rand_i64();
        check_mul_shift64(a, b, (int)(rng64() % 127));
    }
    /* every shift for a set of random pairs */
    for (int i = 0; i < 20000; i++) {
        int64_t a = rand_i64(), b = rand_i64();
        for (int s = 0; s <= 126; s++) check_mul_shift64(a, b, s);
    }
}

int main(void)
{
    setvbuf(stdout, NULL, _IONBF, 0);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sat),
        cmocka_unit_test(test_from_int_floor),
        cmocka_unit_test(test_add_sub),
        cmocka_unit_test(test_mul),
        cmocka_unit_test(test_div),
        cmocka_unit_test(test_mul_shift64),
        cmocka_unit_test(test_round_shift),
        cmocka_unit_test(test_round_shift_extremes),
    };
    return cmocka_run_group_tests_name("fixed", tests, NULL, NULL);
}
