/* mc_line (line.h) against an independent reference: the textbook midpoint Bresenham walked over the
 * whole unclipped line (decision variable 2M - D, minor step when it is > 0), depths from doubles,
 * then filtered to the target. For endpoints far off the target (up to 2^24 away) the reference
 * does not walk: it takes the pixels of the visible columns (rows, for steep lines) from the exact
 * line equation, and is checked against the walk on lines short enough to walk.
 *
 * Checked: the pixel set, the count returned, depths the nearest integer to the exact value (halves
 * towards the start's depth) and the same both ways (a->b and b->a give byte-identical targets), in
 * every octant and on 1x1, 7x5, 5x7, 16x16 and 320x240 targets; the depth test with offsets,
 * NO_DEPTH_TEST and WRITE_DEPTH against a per-pixel expectation; margins around the buffers
 * untouched; the coordinate limit; and, through MC_LINE_STEP_HOOK, that a line 2^25 steps long
 * crossing a 16x16 target costs its pixels there plus a constant (four 27-step divisions at most),
 * and a line inside the target exactly its pixels. The suite builds this program with the hook:
 *   -DMC_LINE_STEP_HOOK()=do { extern unsigned long mc_test_line_steps; mc_test_line_steps++; } while (0)
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include <modelc/line.h>
#include <modelc/rng.h>
#include <modelc/target.h>

unsigned long mc_test_line_steps;

#define LIM (1 << 24)

static const char *vstr(mc_line_vertex v)
{
    static char buf[4][64];
    static int n;
    char *s = buf[n++ & 3];
    snprintf(s, 64, "(%ld,%ld,z%lu)", (long)v.x, (long)v.y, (unsigned long)v.z);
    return s;
}

/* ---- reference ------------------------------------------------------------------------------- */

/* the start's depth of the last line set up: exact halves round towards it */
static double ref_z0;

typedef struct ref_line {
    int64_t x0, y0, x1, y1;   /* from the start: the endpoint with the smaller major coordinate */
    double z0, z1;
    int xmajor;
} ref_line;

static ref_line ref_setup(mc_line_vertex a, mc_line_vertex b)
{
    ref_line L;
    double za = a.z > 0xFFFDu ? 0xFFFD : a.z, zb = b.z > 0xFFFDu ? 0xFFFD : b.z;
    int64_t dx = (int64_t)b.x - a.x, dy = (int64_t)b.y - a.y;
    L.xmajor = llabs(dx) >= llabs(dy);
    int swap = L.xmajor ? b.x < a.x : b.y < a.y;
    if (swap) {
        mc_line_vertex t = a; a = b; b = t;
        double tz = za; za = zb; zb = tz;
    }
    if (dx == 0 && dy == 0) za = zb = fmin(za, zb);
    L.x0 = a.x, L.y0 = a.y, L.x1 = b.x, L.y1 = b.y, L.z0 = za, L.z1 = zb;
    ref_z0 = za;
    return L;
}

/* exp[y * w + x]: the exact depth of each pixel of the line on a w x h target, -1 elsewhere */
static void ref_put(double *exp, int w, int h, int64_t x, int64_t y, double z, uint32_t *count)
{
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    assert_true(exp[y * w + x] < 0);   /* each pixel once */
    exp[y * w + x] = z;
    (*count)++;
}

/* the textbook midpoint walk over the whole line */
static uint32_t ref_walk(mc_line_vertex a, mc_line_vertex b, int w, int h, double *exp)
{
    ref_line L = ref_setup(a, b);
    int64_t du = L.xmajor ? L.x1 - L.x0 : L.y1 - L.y0;
    int64_t dv = L.xmajor ? L.y1 - L.y0 : L.x1 - L.x0;
    int64_t sv = dv < 0 ? -1 : 1, adv = llabs(dv);
    int64_t u = L.xmajor ? L.x0 : L.y0, v = L.xmajor ? L.y0 : L.x0;
    int64_t dec = 2 * adv - du;
    uint32_t count = 0;
    for (int64_t i = 0; i <= du; i++) {
        double z = du ? L.z0 + (L.z1 - L.z0) * (double)i / (double)du : L.z0;
        if (L.xmajor) ref_put(exp, w, h, u, v, z, &count);
        else ref_put(exp, w, h, v, u, z, &count);
        if (dec > 0) {
            v += sv;
            dec -= 2 * du;
        }
        dec += 2 * adv;
        u++;
    }
    return count;
}

/* the same pixels from the line equation, over the visible major coordinates only: step i's minor
 * offset is the integer nearest to i * M / D, halves down (what the walk's "> 0" gives) */
static uint32_t ref_window(mc_line_vertex a, mc_line_vertex b, int w, int h, double *exp)
{
    ref_line L = ref_setup(a, b);
    int64_t u0 = L.xmajor ? L.x0 : L.y0, du = L.xmajor ? L.x1 - L.x0 : L.y1 - L.y0;
    int64_t v0 = L.xmajor ? L.y0 : L.x0, dv = L.xmajor ? L.y1 - L.y0 : L.x1 - L.x0;
    int64_t umax = (L.xmajor ? w : h) - 1;
    uint32_t count = 0;
    int64_t lo = u0 > 0 ? u0 : 0, hi = u0 + du < umax ? u0 + du : umax;
    for (int64_t u = lo; u <= hi; u++) {
        int64_t i = u - u0, k = 0;
        if (du) {
            /* the smallest k with k >= i|dv|/du - 1/2, i.e. 2 du (k + 1) >= 2 i |dv| + du */
            const int64_t num = 2 * i * llabs(dv) + du;
            k = (num + 2 * du - 1) / (2 * du) - 1;
        }
        int64_t v = v0 + (dv < 0 ? -k : k);
        double z = du ? L.z0 + (L.z1 - L.z0) * (double)i / (double)du : L.z0;
        if (L.xmajor) ref_put(exp, w, h, u, v, z, &count);
        else ref_put(exp, w, h, v, u, z, &count);
    }
    return count;
}

/* ---- targets --------------------------------------------------------------------------------- */

typedef struct bench {
    int w, h;
    mc_target t1, t2;
    double *exp, *exp2;
} bench;

static void bench_init(bench *B, int w, int h)
{
    B->w = w, B->h = h;
    size_t n = (size_t)w * h;
    /* exact sizes: under ASan any write outside is reported */
    B->t1 = (mc_target){malloc(n), malloc(n * 2), (uint16_t)w, (uint16_t)h};
    B->t2 = (mc_target){malloc(n), malloc(n * 2), (uint16_t)w, (uint16_t)h};
    B->exp = malloc(n * sizeof(double));
    B->exp2 = malloc(n * sizeof(double));
    assert_non_null(B->t1.color);
    assert_non_null(B->exp2);
}

static void bench_free(bench *B)
{
    free(B->t1.color), free(B->t1.depth), free(B->t2.color), free(B->t2.depth), free(B->exp), free(B->exp2);
}

static const mc_line_style plot = {0, MC_LINE_NO_DEPTH_TEST | MC_LINE_WRITE_DEPTH};

static int fits_walk(mc_line_vertex a, mc_line_vertex b)
{
    return llabs((int64_t)a.x - b.x) <= 70000 && llabs((int64_t)a.y - b.y) <= 70000;
}

/* Draws a->b and b->a and compares them with the reference. Returns the count. */
static uint32_t check_line(bench *B, mc_line_vertex a, mc_line_vertex b)
{
    const int n = B->w * B->h;
    for (int i = 0; i < n; i++) B->exp[i] = -1;
    uint32_t want = fits_walk(a, b) ? ref_walk(a, b, B->w, B->h, B->exp) : ref_window(a, b, B->w, B->h, B->exp);
    mc_clear(&B->t1);
    mc_clear(&B->t2);
    uint32_t got = mc_line(&B->t1, a, b, 7, &plot);
    uint32_t got2 = mc_line(&B->t2, b, a, 7, &plot);
    if (got != want || got2 != want)
        fail_msg("%dx%d %s -> %s: returned %u and %u back, reference has %u pixels", B->w, B->h, vstr(a), vstr(b),
                 got, got2, want);
    for (int i = 0; i < n; i++) {
        const int drawn = B->t1.depth[i] != MC_DEPTH_EMPTY;
        if (drawn != (B->exp[i] >= 0))
            fail_msg("%dx%d %s -> %s: pixel (%d,%d) %s, reference %s", B->w, B->h, vstr(a), vstr(b), i % B->w,
                     i / B->w, drawn ? "drawn" : "not drawn", drawn ? "has not" : "has");
        if (!drawn) continue;
        if (B->t1.color[i] != 7) fail_msg("pixel (%d,%d) colour %d", i % B->w, i / B->w, B->t1.color[i]);
        /* the exact values are multiples of 1/D, computed exactly enough that a half is exactly 0.5 */
        const double err = fabs(B->t1.depth[i] - B->exp[i]);
        if (err > 0.5 || (err == 0.5 && fabs(B->t1.depth[i] - ref_z0) > fabs(B->exp[i] - ref_z0)))
            fail_msg("%dx%d %s -> %s: pixel (%d,%d) depth %u, exact %.4f", B->w, B->h, vstr(a), vstr(b), i % B->w,
                     i / B->w, B->t1.depth[i], B->exp[i]);
    }
    if (memcmp(B->t1.depth, B->t2.depth, (size_t)n * 2) || memcmp(B->t1.color, B->t2.color, (size_t)n))
        fail_msg("%dx%d %s -> %s differs from %s -> %s", B->w, B->h, vstr(a), vstr(b), vstr(b), vstr(a));
    return got;
}

static mc_rng rng;

static int32_t rand_in(int32_t lo, int32_t hi) { return lo + (int32_t)mc_rng_below(&rng, (uint32_t)(hi - lo + 1)); }

static uint32_t rand_z(void)
{
    switch (mc_rng_below(&rng, 8)) {
    case 0: return 0;
    case 1: return 0xFFFD;
    case 2: return mc_rng_next(&rng);   /* mostly above the limit: clamped */
    default: return mc_rng_below(&rng, 0xFFFE);
    }
}

static mc_line_vertex rand_vertex(int32_t lo_x, int32_t hi_x, int32_t lo_y, int32_t hi_y)
{
    mc_line_vertex v = {rand_in(lo_x, hi_x), rand_in(lo_y, hi_y), rand_z()};
    return v;
}

static const int sizes[][2] = {{1, 1}, {7, 5}, {5, 7}, {16, 16}, {320, 240}};

/* ---- tests ------------------------------------------------------------------------------------ */

/* the window reference is the walk's pixel set, on lines both can do */
static void test_references_agree(void **state)
{
    (void)state;
    mc_rng_seed(&rng, 1, 1);
    bench B;
    bench_init(&B, 16, 16);
    for (int it = 0; it < 20000; it++) {
        int32_t r = it % 3 == 0 ? 40 : it % 3 == 1 ? 400 : 30000;
        mc_line_vertex a = rand_vertex(-r, r, -r, r), b = rand_vertex(-r, r, -r, r);
        if (it % 2) {   /* through the target */
            int32_t px = rand_in(-1, 16), py = rand_in(-1, 16);
            b.x = 2 * px - a.x, b.y = 2 * py - a.y;
        }
        for (int i = 0; i < 256; i++) B.exp[i] = B.exp2[i] = -1;
        uint32_t n1 = ref_walk(a, b, 16, 16, B.exp), n2 = ref_window(a, b, 16, 16, B.exp2);
        assert_int_equal(n1, n2);
        for (int i = 0; i < 256; i++) {
            if (B.exp[i] != B.exp2[i])
                fail_msg("%s -> %s: references differ at (%d,%d)", vstr(a), vstr(b), i % 16, i / 16);
        }
    }
    /* a known line: (0,0)-(4,2) has ties at x = 1 and 3, which stay down */
    for (int i = 0; i < 256; i++) B.exp[i] = -1;
    ref_walk((mc_line_vertex){0, 0, 0}, (mc_line_vertex){4, 2, 0}, 16, 16, B.exp);
    assert_true(B.exp[0 * 16 + 1] >= 0 && B.exp[1 * 16 + 2] >= 0 && B.exp[1 * 16 + 3] >= 0 && B.exp[2 * 16 + 4] >= 0);
    bench_free(&B);
}

static void test_special_lines(void **state)
{
    (void)state;
    mc_rng_seed(&rng, 2, 1);
    for (unsigned si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        bench B;
        const int w = sizes[si][0], h = sizes[si][1];
        bench_init(&B, w, h);
        for (int it = 0; it < 300; it++) {
            int32_t x = rand_in(-3, w + 2), y = rand_in(-3, h + 2), len = rand_in(0, 2 * (w > h ? w : h) + 4);
            uint32_t z0 = rand_z(), z1 = rand_z();
            check_line(&B, (mc_line_vertex){x, y, z0}, (mc_line_vertex){x, y, z1});            /* point */
            check_line(&B, (mc_line_vertex){x - len, y, z0}, (mc_line_vertex){x, y, z1});      /* horizontal */
            check_line(&B, (mc_line_vertex){x, y - len, z0}, (mc_line_vertex){x, y, z1});      /* vertical */
            check_line(&B, (mc_line_vertex){x - len, y - len, z0}, (mc_line_vertex){x, y, z1}); /* diagonals */
            check_line(&B, (mc_line_vertex){x - len, y + len, z0}, (mc_line_vertex){x, y, z1});
        }
        /* a single pixel keeps the nearer depth, and draws only when on the target */
        mc_clear(&B.t1);
        assert_int_equal(mc_line(&B.t1, (mc_line_vertex){0, 0, 900}, (mc_line_vertex){0, 0, 300}, 3, &plot), 1);
        assert_int_equal(B.t1.depth[0], 300);
        assert_int_equal(mc_line(&B.t1, (mc_line_vertex){-1, 0, 9}, (mc_line_vertex){-1, 0, 9}, 3, &plot), 0);
        assert_int_equal(mc_line(&B.t1, (mc_line_vertex){w, h - 1, 9}, (mc_line_vertex){w, h - 1, 9}, 3, &plot), 0);
        bench_free(&B);
    }
}

static void test_random_lines(void **state)
{
    (void)state;
    mc_rng_seed(&rng, 3, 1);
    for (unsigned si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        bench B;
        const int w = sizes[si][0], h = sizes[si][1];
        bench_init(&B, w, h);
        const int lines = w * h > 1000 ? 400 : 6000;
        uint32_t total = 0;
        for (int it = 0; it < lines; it++) {
            mc_line_vertex a, b;
            switch (it % 4) {
            case 0:   /* near or on the target */
                a = rand_vertex(-w, 2 * w, -h, 2 * h), b = rand_vertex(-w, 2 * w, -h, 2 * h);
                break;
            case 1:   /* inside: no clipping */
                a = rand_vertex(0, w - 1, 0, h - 1), b = rand_vertex(0, w - 1, 0, h - 1);
                break;
            case 2:   /* long, through a random point near the target */
            case 3: {
                int32_t r = it % 4 == 2 ? 20000 : LIM - 2 * w - 2 * h;
                int32_t px = rand_in(-2, w + 1), py = rand_in(-2, h + 1);
                a = rand_vertex(-r, r, -r, r);
                b = (mc_line_vertex){2 * px - a.x, 2 * py - a.y, rand_z()};
                break;
            }
            }
            total += check_line(&B, a, b);
        }
        assert_true(total > (uint32_t)lines / 4);   /* the lines did reach the targets */
        bench_free(&B);
    }
}

/* lines from far away that graze a corner of the target, or miss it by a pixel */
static void test_corners_and_limits(void **state)
{
    (void)state;
    mc_rng_seed(&rng, 4, 1);
    bench B;
    bench_init(&B, 7, 5);
    const int32_t cx[4] = {0, 6, 0, 6}, cy[4] = {0, 0, 4, 4};
    uint32_t hits = 0, misses = 0;
    for (int it = 0; it < 4000; it++) {
        const int c = it % 4;
        int32_t px = cx[c] + rand_in(-1, 1), py = cy[c] + rand_in(-1, 1);
        int32_t r = it % 3 == 0 ? 1000 : it % 3 == 1 ? 1000000 : LIM - 20;
        /* the far end on the side away from the corner */
        int32_t fx = rand_in(0, r) * (cx[c] ? 1 : -1), fy = rand_in(0, r) * (cy[c] ? 1 : -1);
        mc_line_vertex a = {px + fx, py - fy, rand_z()}, b = {px - fx, py + fy, rand_z()};
        if (check_line(&B, a, b)) hits++;
        else misses++;
    }
    assert_true(hits > 100 && misses > 100);
    /* endpoints exactly at +-2^24, through the target */
    for (int it = 0; it < 2000; it++) {
        int32_t e = rand_in(-LIM, LIM), py = rand_in(-1, 5), px = rand_in(-1, 7);
        mc_line_vertex a, b;
        switch (it % 5) {
        case 0: a = (mc_line_vertex){-LIM, e, rand_z()}, b = (mc_line_vertex){LIM, rand_in(-LIM, LIM), rand_z()}; break;
        case 1: a = (mc_line_vertex){e, -LIM, rand_z()}, b = (mc_line_vertex){rand_in(-LIM, LIM), LIM, rand_z()}; break;
        case 2: a = (mc_line_vertex){-LIM, 2 * py - e, rand_z()}, b = (mc_line_vertex){LIM, e, rand_z()};
                if (a.y < -LIM || a.y > LIM) a.y = py;
                break;
        case 3: a = (mc_line_vertex){2 * px - e, -LIM, rand_z()}, b = (mc_line_vertex){e, LIM, rand_z()};
                if (a.x < -LIM || a.x > LIM) a.x = px;
                break;
        default: a = (mc_line_vertex){-LIM, -LIM, rand_z()}, b = (mc_line_vertex){LIM, LIM, rand_z()};
                 if (it % 2) a.y = LIM, b.y = -LIM + 4 + (int32_t)mc_rng_below(&rng, 2);
        }
        check_line(&B, a, b);
    }
    /* the main diagonal through the origin: pixels (0,0) .. (4,4) */
    assert_int_equal(check_line(&B, (mc_line_vertex){-LIM, -LIM, 0}, (mc_line_vertex){LIM, LIM, 0}), 5);
    /* beyond the limit nothing is drawn, even with the other end on the target */
    const int32_t bad[] = {LIM + 1, -LIM - 1, INT32_MAX, INT32_MIN};
    for (int i = 0; i < 4; i++) {
        mc_clear(&B.t1);
        assert_int_equal(mc_line(&B.t1, (mc_line_vertex){bad[i], 2, 5}, (mc_line_vertex){3, 2, 5}, 1, &plot), 0);
        assert_int_equal(mc_line(&B.t1, (mc_line_vertex){3, 2, 5}, (mc_line_vertex){3, bad[i], 5}, 1, &plot), 0);
        for (int p = 0; p < 35; p++) assert_int_equal(B.t1.depth[p], MC_DEPTH_EMPTY);
    }
    /* an empty target */
    mc_target empty = {B.t1.color, B.t1.depth, 0, 5};
    assert_int_equal(mc_line(&empty, (mc_line_vertex){0, 0, 5}, (mc_line_vertex){3, 2, 5}, 1, &plot), 0);
    bench_free(&B);
}

/* the depth test, pixel by pixel: drawn iff max(z - offset, 0) < depth (or NO_DEPTH_TEST); the
 * colour always, the depth only with WRITE_DEPTH; pixels off the line untouched */
static void test_depth_test(void **state)
{
    (void)state;
    mc_rng_seed(&rng, 5, 1);
    bench B;
    const int w = 16, h = 16, n = w * h;
    bench_init(&B, w, h);
    uint8_t c0[256];
    uint16_t d0[256];
    unsigned drawn = 0, hidden = 0;
    for (int it = 0; it < 20000; it++) {
        mc_line_vertex a = rand_vertex(-8, 23, -8, 23), b = rand_vertex(-8, 23, -8, 23);
        /* the line's own depths (checked against the reference by the other tests) */
        mc_clear(&B.t2);
        uint32_t want = mc_line(&B.t2, a, b, 1, &plot);
        mc_line_style st = {0, (uint8_t)mc_rng_below(&rng, 4)};
        switch (mc_rng_below(&rng, 4)) {
        case 0: st.depth_offset = 0; break;
        case 1: st.depth_offset = (uint16_t)mc_rng_below(&rng, 8); break;
        case 2: st.depth_offset = (uint16_t)mc_rng_below(&rng, 65536); break;
        default: st.depth_offset = 0xFFFF;
        }
        /* target depths at and around each line pixel's depth - offset, and anything elsewhere */
        for (int i = 0; i < n; i++) {
            c0[i] = (uint8_t)mc_rng_next(&rng);
            const uint32_t k = mc_rng_below(&rng, 6);
            if (B.t2.depth[i] != MC_DEPTH_EMPTY && k < 4) {
                int32_t v = (int32_t)B.t2.depth[i] - st.depth_offset + (int32_t)k - 1;   /* -1, 0, +1, +2 */
                d0[i] = (uint16_t)(v < 0 ? 0 : v);
            } else {
                d0[i] = k == 4 ? (uint16_t)(mc_rng_below(&rng, 2) ? 0 : 0xFFFF) : (uint16_t)mc_rng_next(&rng);
            }
        }
        memcpy(B.t1.color, c0, n);
        memcpy(B.t1.depth, d0, 2 * (size_t)n);
        const int null_style = st.depth_offset == 0 && st.flags == 0 && it % 2;
        const uint32_t got = mc_line(&B.t1, a, b, 200, null_style ? NULL : &st);
        assert_int_equal(got, want);
        for (int i = 0; i < n; i++) {
            const int on = B.t2.depth[i] != MC_DEPTH_EMPTY;
            const uint32_t z = B.t2.depth[i];
            const uint32_t zt = z > st.depth_offset ? z - st.depth_offset : 0;
            const int draw = on && ((st.flags & MC_LINE_NO_DEPTH_TEST) || zt < d0[i]);
            const uint8_t wc = draw ? 200 : c0[i];
            const uint16_t wd = draw && (st.flags & MC_LINE_WRITE_DEPTH) ? (uint16_t)z : d0[i];
            if (B.t1.color[i] != wc || B.t1.depth[i] != wd)
                fail_msg("%s -> %s offset %u flags %u: pixel (%d,%d) z %u on depth %u: colour %u depth %u, want %u %u",
                         vstr(a), vstr(b), st.depth_offset, st.flags, i % w, i / w, z, d0[i], B.t1.color[i], B.t1.depth[i],
                         wc, wd);
            if (on) {
                if (draw) drawn++;
                else hidden++;
            }
        }
    }
    assert_true(drawn > 1000 && hidden > 1000);

    /* hand-made: a face at depth 100 under a line at depth 100 */
    for (int i = 0; i < n; i++) B.t1.depth[i] = 100, B.t1.color[i] = 0;
    mc_line_vertex a = {0, 3, 100}, b = {15, 3, 100};
    mc_line_style st = {0, 0};
    mc_line(&B.t1, a, b, 9, &st);   /* 100 < 100 fails: hidden */
    assert_int_equal(B.t1.color[3 * w + 5], 0);
    st.depth_offset = 1;
    mc_line(&B.t1, a, b, 9, &st);   /* 99 < 100: shown, depth kept */
    assert_int_equal(B.t1.color[3 * w + 5], 9);
    assert_int_equal(B.t1.depth[3 * w + 5], 100);
    st.depth_offset = 200;           /* saturates at 0, still not < 0 */
    B.t1.depth[3 * w + 6] = 0;
    mc_line(&B.t1, a, b, 10, &st);
    assert_int_equal(B.t1.color[3 * w + 6], 9);
    assert_int_equal(B.t1.color[3 * w + 7], 10);
    st.flags = MC_LINE_NO_DEPTH_TEST;
    mc_line(&B.t1, a, b, 11, &st);
    assert_int_equal(B.t1.color[3 * w + 6], 11);
    assert_int_equal(B.t1.depth[3 * w + 6], 0);
    /* with WRITE_DEPTH a nearer line hides a farther one drawn after it (they cross at (7,7)); without,
     * it does not */
    const mc_line_vertex d0a = {0, 0, 50}, d0b = {14, 14, 50}, d1a = {0, 14, 60}, d1b = {14, 0, 60};
    mc_clear(&B.t1);
    mc_line(&B.t1, d0a, d0b, 1, &(mc_line_style){0, MC_LINE_WRITE_DEPTH});
    mc_line(&B.t1, d1a, d1b, 2, NULL);
    assert_int_equal(B.t1.color[7 * w + 7], 1);
    assert_int_equal(B.t1.depth[7 * w + 7], 50);
    assert_int_equal(B.t1.color[8 * w + 6], 2);
    assert_int_equal(B.t1.depth[8 * w + 6], MC_DEPTH_EMPTY);
    mc_clear(&B.t1);
    mc_line(&B.t1, d0a, d0b, 1, NULL);
    mc_line(&B.t1, d1a, d1b, 2, NULL);
    assert_int_equal(B.t1.color[7 * w + 7], 2);
    assert_int_equal(B.t1.depth[7 * w + 7], MC_DEPTH_EMPTY);
    /* endpoint depths above the limit are clamped: no written depth reaches MC_DEPTH_EMPTY - 1 */
    mc_clear(&B.t1);
    mc_line(&B.t1, (mc_line_vertex){0, 0, 0xFFFF}, (mc_line_vertex){15, 9, 0xFFFFFFFFu}, 1, &plot);
    assert_int_equal(B.t1.depth[0], 0xFFFD);
    assert_int_equal(B.t1.depth[9 * w + 15], 0xFFFD);
    bench_free(&B);
}

/* buffers inside larger arrays: the margins stay as they were */
static void test_guard_zones(void **state)
{
    (void)state;
    mc_rng_seed(&rng, 6, 1);
    enum { G = 4096 };
    for (unsigned si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        const int w = sizes[si][0], h = sizes[si][1], n = w * h;
        uint8_t *cb = malloc((size_t)n + 2 * G);
        uint16_t *db = malloc(((size_t)n + 2 * G) * 2);
        assert_non_null(cb);
        assert_non_null(db);
        for (int i = 0; i < n + 2 * G; i++) cb[i] = 0xA5, db[i] = 0x5A5A;
        mc_target t = {cb + G, db + G, (uint16_t)w, (uint16_t)h};
        mc_clear(&t);
        uint32_t total = 0;
        for (int it = 0; it < 20000; it++) {
            int32_t r = it % 3 == 0 ? 2 * (w + h) : it % 3 == 1 ? 5000 : LIM;
            mc_line_vertex a = rand_vertex(-r, r, -r, r), b = rand_vertex(-r, r, -r, r);
            if (it % 2) {
                int32_t px = rand_in(-2, w + 1), py = rand_in(-2, h + 1), q = LIM - 2 * (w + h);
                if (a.x < -q || a.x > q) a.x /= 2;
                if (a.y < -q || a.y > q) a.y /= 2;
                b.x = 2 * px - a.x, b.y = 2 * py - a.y;
            }
            const mc_line_style st = {(uint16_t)mc_rng_below(&rng, 3), (uint8_t)mc_rng_below(&rng, 4)};
            total += mc_line(&t, a, b, (uint8_t)it, &st);
        }
        for (int i = 0; i < G; i++) {
            if (cb[i] != 0xA5 || cb[G + n + i] != 0xA5 || db[i] != 0x5A5A || db[G + n + i] != 0x5A5A)
                fail_msg("%dx%d: margin written at %d", w, h, i);
        }
        assert_true(total > 1000);
        free(cb);
        free(db);
    }
}

/* work: the loops' iterations are the pixels on the target plus at most four 27-step divisions
 * (the clip entry); none at all for a line inside the target */
static void test_work_follows_pixels(void **state)
{
    (void)state;
#ifndef MC_LINE_STEP_HOOK
    fail_msg("build with -DMC_LINE_STEP_HOOK()=... (see the comment at the top)");
#else
    mc_rng_seed(&rng, 7, 1);
    bench B;
    bench_init(&B, 16, 16);
    unsigned long worst = 0;
    for (int it = 0; it < 3000; it++) {
        mc_line_vertex a, b;
        if (it == 0) {
            a = (mc_line_vertex){-LIM, -LIM + 3, 0}, b = (mc_line_vertex){LIM, LIM - 1, 0xFFFD};
        } else {
            const int32_t px = rand_in(0, 15), py = rand_in(0, 15);
            a = (mc_line_vertex){-LIM + 32, rand_in(-LIM / 2, LIM / 2), rand_z()};
            if (it % 2) a = (mc_line_vertex){a.y, -LIM + 32, a.z};
            b = (mc_line_vertex){2 * px - a.x, 2 * py - a.y, rand_z()};
        }
        mc_test_line_steps = 0;
        const uint32_t count = mc_line(&B.t1, a, b, 1, &plot);
        assert_true(count >= 1);
        assert_true(mc_test_line_steps >= count);
        const unsigned long extra = mc_test_line_steps - count;
        if (extra > 4 * 27) fail_msg("%s -> %s: %lu steps for %u pixels", vstr(a), vstr(b), mc_test_line_steps, count);
        if (extra > worst) worst = extra;
    }
    print_message("# info: at most %lu steps beyond the pixels on a clipped line\n", worst);
    for (int it = 0; it < 3000; it++) {
        mc_line_vertex a = rand_vertex(0, 15, 0, 15), b = rand_vertex(0, 15, 0, 15);
        mc_test_line_steps = 0;
        const uint32_t count = mc_line(&B.t1, a, b, 1, &plot);
        assert_int_equal(mc_test_line_steps, count);
    }
    /* a line of 2^25 steps missing the target by a pixel (y = x - 16): a few divisions */
    mc_test_line_steps = 0;
    const mc_line_vertex m0 = {-LIM + 16, -LIM, 0}, m1 = {LIM, LIM - 16, 0};
    assert_int_equal(mc_line(&B.t1, m0, m1, 1, &plot), 0);
    assert_true(mc_test_line_steps <= 4 * 27);
    bench_free(&B);
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_references_agree),
        cmocka_unit_test(test_special_lines),
        cmocka_unit_test(test_random_lines),
        cmocka_unit_test(test_corners_and_limits),
        cmocka_unit_test(test_depth_test),
        cmocka_unit_test(test_guard_zones),
        cmocka_unit_test(test_work_follows_pixels),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
