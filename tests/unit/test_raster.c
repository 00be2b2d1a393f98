/* The triangle rasterizer (modelc/raster.h) against its double-precision reference
 * (runtime/ref/raster_ref.c, which tests every pixel on its own) and against the properties the
 * top-left rule exists for:
 *   - random triangles, from slivers and sub-pixel specks to triangles far larger than the target,
 *     partly or wholly off it, corners on pixel centres and edges, on 1x1, 7x5, 33x17, 320x240,
 *     65535x1 and 1x65535 targets (the longest spans and columns depth is stepped over): the
 *     same pixels covered, the same count returned, depth within 3/4 of the exact plane and equal
 *     to its rounding away from half-integers, inside the corners' depths; the same pixels
 *     whatever the corner order; culling as the reference's sign rule;
 *   - tilings: random triangulations of a rectangle, corners in random order, cover each pixel
 *     centre of the half-open rectangle once and nothing else; fans around a vertex (on a pixel
 *     centre, spokes along the axes and diagonals) cover each centre inside the fan once;
 *   - triangles of a few pixels with every corner on or beside a pixel centre or edge, partly
 *     off the target: the bounding-box tests that reject a triangle before any setup;
 *   - back-face culling by the sign rule; the depth test (strictly nearer wins, equal keeps);
 *   - coordinates at +-2^22 accepted, one beyond rejected; degenerate triangles draw nothing;
 *   - mc_raster_slope (a pixel's worth of the steepest depth slope) against the gradient in doubles;
 *   - every target sits in a larger array whose margins must stay untouched (checked after
 *     every draw).
 * Random numbers: PCG32 (modelc/rng.h) with fixed seeds.
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

#include <modelc/raster.h>
#include <modelc/rng.h>
#include "../../runtime/ref/raster_ref.h"

#define L MC_RASTER_COORD_LIMIT
#define GUARD 67
#define ZTOP (MC_DEPTH_EMPTY - 2u)

/* a target inside guard margins, with the reference's scratch */
typedef struct gtarget {
    mc_target t;
    uint8_t *cmem;
    uint16_t *dmem;
    uint8_t *cov;
    double *ref;
    unsigned n;
} gtarget;

static gtarget gt_new(unsigned w, unsigned h)
{
    gtarget g;
    g.n = w * h;
    g.cmem = malloc(g.n + 2 * GUARD);
    g.dmem = malloc((g.n + 2 * GUARD) * sizeof *g.dmem);
    g.cov = malloc(g.n ? g.n : 1);
    g.ref = malloc((g.n ? g.n : 1) * sizeof *g.ref);
    assert_non_null(g.cmem);
    assert_non_null(g.dmem);
    for (unsigned i = 0; i < g.n + 2 * GUARD; i++) { g.cmem[i] = 0xA5; g.dmem[i] = 0x5AA5; }
    g.t.color = g.cmem + GUARD;
    g.t.depth = g.dmem + GUARD;
    g.t.width = (uint16_t)w;
    g.t.height = (uint16_t)h;
    mc_clear(&g.t);
    return g;
}

static void gt_free(gtarget *g)
{
    free(g->cmem); free(g->dmem); free(g->cov); free(g->ref);
}

static void gt_check_guards(const gtarget *g)
{
    for (unsigned i = 0; i < GUARD; i++) {
        assert_int_equal(g->cmem[i], 0xA5);
        assert_int_equal(g->cmem[GUARD + g->n + i], 0xA5);
        assert_int_equal(g->dmem[i], 0x5AA5);
        assert_int_equal(g->dmem[GUARD + g->n + i], 0x5AA5);
    }
}

static uint32_t draw(gtarget *g, const mc_raster_vertex v[3], uint8_t color, unsigned flags)
{
    const uint32_t n = mc_raster_triangle(&g->t, v, color, flags);
    gt_check_guards(g);
    return n;
}

static void print_tri(const char *what, const gtarget *g, const mc_raster_vertex v[3], unsigned flags)
{
    print_error("%s on %ux%u, flags %u: (%ld, %ld, %lu) (%ld, %ld, %lu) (%ld, %ld, %lu)\n", what,
                (unsigned)g->t.width, (unsigned)g->t.height, flags, (long)v[0].x, (long)v[0].y,
                (unsigned long)v[0].z, (long)v[1].x, (long)v[1].y, (unsigned long)v[1].z, (long)v[2].x,
                (long)v[2].y, (unsigned long)v[2].z);
}

static int64_t rnd_range(mc_rng *r, int64_t lo, int64_t hi)   /* inclusive, hi - lo < 2^32 */
{
    return lo + (int64_t)mc_rng_below(r, (uint32_t)(hi - lo + 1));
}

static int32_t clampc(int64_t c)
{
    return (int32_t)(c < -L ? -L : c > L ? L : c);
}

/* Clears the target, draws v and compares everything with the reference. */
static void check_against_ref(gtarget *g, const mc_raster_vertex v[3], unsigned flags)
{
    mc_clear(&g->t);
    const uint32_t got = draw(g, v, 7, flags);
    const uint32_t want = mc_raster_ref_triangle(g->t.width, g->t.height, v, flags, g->cov, g->ref);
    uint32_t zmin = ZTOP, zmax = 0;
    for (int k = 0; k < 3; k++) {
        const uint32_t z = v[k].z > ZTOP ? ZTOP : v[k].z;
        if (z < zmin) zmin = z;
        if (z > zmax) zmax = z;
    }
    if (got != want) {
        print_tri("count", g, v, flags);
        fail_msg("returned %u, reference covers %u", got, want);
    }
    for (unsigned i = 0; i < g->n; i++) {
        const uint16_t d = g->t.depth[i];
        if (!g->cov[i]) {
            if (d != MC_DEPTH_EMPTY || g->t.color[i] != 0) {
                print_tri("coverage", g, v, flags);
                fail_msg("pixel (%u, %u) drawn, the reference does not cover it", i % g->t.width, i / g->t.width);
            }
            continue;
        }
        if (d == MC_DEPTH_EMPTY || g->t.color[i] != 7) {
            print_tri("coverage", g, v, flags);
            fail_msg("pixel (%u, %u) not drawn, the reference covers it", i % g->t.width, i / g->t.width);
        }
        const double e = g->ref[i], err = fabs(d - e), half = fabs(e - floor(e) - 0.5);
        if (err > 0.75 + 1e-9 || d < zmin || d > zmax || (half > 0.25 + 1e-9 && d != (uint16_t)floor(e + 0.5))) {
            print_tri("depth", g, v, flags);
            fail_msg("pixel (%u, %u): depth %u, exact %.6f", i % g->t.width, i / g->t.width, d, e);
        }
    }
}

/* A random coordinate pair near a target of w x h pixels, of one of several kinds. */
static void random_triangle(mc_rng *r, unsigned w, unsigned h, mc_raster_vertex v[3])
{
    const int64_t W = 16 * (int64_t)w, H = 16 * (int64_t)h;
    const unsigned kind = mc_rng_below(r, 8);
    const int64_t cx = rnd_range(r, -W / 2 - 64, W + W / 2 + 64), cy = rnd_range(r, -H / 2 - 64, H + H / 2 + 64);
    int64_t s;   /* spread of the corners around (cx, cy) */
    switch (kind) {
    case 0: s = rnd_range(r, 1, 40); break;                             /* specks, a few pixels */
    case 1: s = rnd_range(r, 16, 16 * (int64_t)(w > h ? w : h) + 16); break;   /* target-sized */
    case 2: s = (int64_t)1 << rnd_range(r, 8, 22); break;               /* up to far larger */
    default: s = rnd_range(r, 8, 16 * 64); break;
    }
    for (int k = 0; k < 3; k++) {
        v[k].x = clampc(cx + rnd_range(r, -s, s));
        v[k].y = clampc(cy + rnd_range(r, -s, s));
    }
    if (kind == 3) {   /* sliver: the third corner on or beside the line of the other two */
        const int64_t t = rnd_range(r, -256, 512);
        v[2].x = clampc(v[0].x + (int64_t)(v[1].x - v[0].x) * t / 256 + rnd_range(r, -2, 2));
        v[2].y = clampc(v[0].y + (int64_t)(v[1].y - v[0].y) * t / 256 + rnd_range(r, -2, 2));
    } else if (kind == 4) {   /* corners on pixel centres and pixel edges: ties everywhere */
        for (int k = 0; k < 3; k++) {
            v[k].x = clampc((int64_t)v[k].x / 8 * 8);
            v[k].y = clampc((int64_t)v[k].y / 8 * 8);
        }
    } else if (kind == 5) {   /* axis-aligned edges */
        v[1].y = v[0].y;
        v[2].x = mc_rng_below(r, 2) ? v[0].x : v[1].x;
    } else if (kind == 6) {   /* corners at the coordinate limits */
        for (int k = 0; k < 3; k++) {
            if (mc_rng_below(r, 2)) v[k].x = mc_rng_below(r, 2) ? L : -L;
            if (mc_rng_below(r, 2)) v[k].y = mc_rng_below(r, 2) ? L : -L;
        }
    }
    /* depths: anything, one plane level, a narrow range, or beyond the largest (clamped) */
    const unsigned zk = mc_rng_below(r, 5);
    const uint32_t z0 = mc_rng_below(r, ZTOP + 1);
    for (int k = 0; k < 3; k++) {
        switch (zk) {
        case 0: v[k].z = z0; break;
        case 1: v[k].z = z0 / 2 + mc_rng_below(r, 5); break;
        case 2: v[k].z = mc_rng_below(r, 2) ? 0 : ZTOP; break;
        case 3: v[k].z = ZTOP - 3 + mc_rng_below(r, 8); break;
        default: v[k].z = mc_rng_below(r, ZTOP + 1); break;
        }
    }
}

static void random_against_ref(unsigned w, unsigned h, int count, uint64_t seed)
{
    gtarget g = gt_new(w, h);
    mc_rng r;
    mc_rng_seed(&r, seed, 3);
    uint8_t *first = malloc(g.n);
    assert_non_null(first);
    for (int it = 0; it < count; it++) {
        mc_raster_vertex v[3];
        random_triangle(&r, w, h, v);
        check_against_ref(&g, v, 0);
        /* the same pixels in every corner order, either orientation */
        for (unsigned i = 0; i < g.n; i++) first[i] = g.t.depth[i] != MC_DEPTH_EMPTY;
        static const int perm[5][3] = {{1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
        const int p = (int)mc_rng_below(&r, 5);
        const mc_raster_vertex u[3] = {v[perm[p][0]], v[perm[p][1]], v[perm[p][2]]};
        mc_clear(&g.t);
        const uint32_t n = draw(&g, u, 1, 0);
        uint32_t m = 0;
        for (unsigned i = 0; i < g.n; i++) {
            assert_int_equal(first[i], g.t.depth[i] != MC_DEPTH_EMPTY);
            m += first[i];
        }
        assert_int_equal(n, m);
        /* culling draws exactly the front faces */
        check_against_ref(&g, v, MC_RASTER_CULL_BACK);
    }
    free(first);
    gt_free(&g);
}

static void test_random_1x1(void **state) { (void)state; random_against_ref(1, 1, 30000, 11); }
static void test_random_7x5(void **state) { (void)state; random_against_ref(7, 5, 20000, 12); }
static void test_random_33x17(void **state) { (void)state; random_against_ref(33, 17, 4000, 13); }
static void test_random_320x240(void **state) { (void)state; random_against_ref(320, 240, 150, 14); }
/* the widest and tallest targets: the longest spans and the most rows depth is stepped over */
static void test_random_65535x1(void **state) { (void)state; random_against_ref(65535, 1, 150, 15); }
static void test_random_1x65535(void **state) { (void)state; random_against_ref(1, 65535, 150, 16); }

/* cnt[i] += 1 for each pixel one triangle draws (into an emptied target); checks the count returned */
static void accumulate(gtarget *g, const mc_raster_vertex v[3], unsigned *cnt)
{
    mc_clear(&g->t);
    const uint32_t n = draw(g, v, 3, 0);
    uint32_t m = 0;
    for (unsigned i = 0; i < g->n; i++)
        if (g->t.depth[i] != MC_DEPTH_EMPTY) { cnt[i]++; m++; }
    assert_int_equal(n, m);
}

/* a coordinate, often snapped to a multiple of 8: pixel centres and pixel edges */
static int32_t snap(mc_rng *r, int64_t c)
{
    return clampc(mc_rng_below(r, 3) ? (c >= 0 ? c / 8 * 8 : -((-c) / 8 * 8)) : c);
}

static void tilings(unsigned w, unsigned h, int count, uint64_t seed)
{
    gtarget g = gt_new(w, h);
    unsigned *cnt = malloc(g.n * sizeof *cnt);
    assert_non_null(cnt);
    mc_rng r;
    mc_rng_seed(&r, seed, 5);
    enum { MAXC = 9 };
    int32_t px[MAXC + 1][MAXC + 1], py[MAXC + 1][MAXC + 1];
    for (int it = 0; it < count; it++) {
        memset(cnt, 0, g.n * sizeof *cnt);
        const int nx = 1 + (int)mc_rng_below(&r, MAXC), ny = 1 + (int)mc_rng_below(&r, MAXC);
        /* cells of at least 40 subpixels; the rectangle may stick out of the target */
        const int32_t cw = 40 + 8 * (int32_t)mc_rng_below(&r, 2 * w + 8), ch = 40 + 8 * (int32_t)mc_rng_below(&r, 2 * h + 8);
        const int32_t x0 = snap(&r, rnd_range(&r, -cw * nx / 2, 16 * (int64_t)w - cw * nx / 2));
        const int32_t y0 = snap(&r, rnd_range(&r, -ch * ny / 2, 16 * (int64_t)h - ch * ny / 2));
        const int32_t x1 = x0 + cw * nx, y1 = y0 + ch * ny;
        for (int a = 0; a <= nx; a++) {
            for (int b = 0; b <= ny; b++) {
                /* points move less than a fifth of a cell, along the border only on the border */
                int64_t x = x0 + (int64_t)cw * a, y = y0 + (int64_t)ch * b;
                if (a > 0 && a < nx) x = snap(&r, x + rnd_range(&r, -cw / 5, cw / 5));
                if (b > 0 && b < ny) y = snap(&r, y + rnd_range(&r, -ch / 5, ch / 5));
                px[a][b] = (int32_t)x;
                py[a][b] = (int32_t)y;
            }
        }
        for (int a = 0; a < nx; a++) {
            for (int b = 0; b < ny; b++) {
                const mc_raster_vertex c00 = {px[a][b], py[a][b], 100}, c10 = {px[a + 1][b], py[a + 1][b], 200};
                const mc_raster_vertex c01 = {px[a][b + 1], py[a][b + 1], 300};
                const mc_raster_vertex c11 = {px[a + 1][b + 1], py[a + 1][b + 1], 400};
                mc_raster_vertex tri[2][3];
                if (mc_rng_below(&r, 2)) {
                    tri[0][0] = c00; tri[0][1] = c10; tri[0][2] = c11;
                    tri[1][0] = c00; tri[1][1] = c11; tri[1][2] = c01;
                } else {
                    tri[0][0] = c00; tri[0][1] = c10; tri[0][2] = c01;
                    tri[1][0] = c10; tri[1][1] = c11; tri[1][2] = c01;
                }
                for (int k = 0; k < 2; k++) {
                    if (mc_rng_below(&r, 2)) {   /* the other orientation */
                        const mc_raster_vertex s = tri[k][1];
                        tri[k][1] = tri[k][2];
                        tri[k][2] = s;
                    }
                    accumulate(&g, tri[k], cnt);
                }
            }
        }
        for (unsigned i = 0; i < g.n; i++) {
            const int32_t cx = 16 * (int32_t)(i % w) + 8, cy = 16 * (int32_t)(i / w) + 8;
            const unsigned want = x0 <= cx && cx < x1 && y0 <= cy && cy < y1;
            if (cnt[i] != want)
                fail_msg("tiling %d of [%ld, %ld) x [%ld, %ld) in %dx%d cells: pixel (%u, %u) covered %u times",
                         it, (long)x0, (long)x1, (long)y0, (long)y1, nx, ny, i % w, i / w, cnt[i]);
        }
    }
    free(cnt);
    gt_free(&g);
}

static void test_tiling_rectangles(void **state)
{
    (void)state;
    tilings(61, 47, 300, 21);
    tilings(7, 5, 300, 22);
    tilings(320, 240, 6, 23);
}

/* (b - a) x (p - a), exact in 64 bits for these coordinates */
static int64_t cross64(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t px, int64_t py)
{
    return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

static void test_tiling_fans(void **state)
{
    (void)state;
    const unsigned w = 45, h = 37;
    gtarget g = gt_new(w, h);
    unsigned *cnt = malloc(g.n * sizeof *cnt);
    assert_non_null(cnt);
    mc_rng r;
    mc_rng_seed(&r, 31, 7);
    enum { MAXN = 16 };
    int done = 0;
    while (done < 1500) {
        const int n = 3 + (int)mc_rng_below(&r, MAXN - 2);
        int64_t cx = rnd_range(&r, -64, 16 * w + 64), cy = rnd_range(&r, -64, 16 * h + 64);
        if (mc_rng_below(&r, 2)) { cx = cx / 16 * 16 + 8; cy = cy / 16 * 16 + 8; }   /* on a pixel centre */
        double ang[MAXN];
        for (int k = 0; k < n; k++)   /* a quarter of the spokes along the axes and diagonals */
            ang[k] = mc_rng_below(&r, 4) ? mc_rng_next(&r) * (2 * M_PI / 4294967296.0) : mc_rng_below(&r, 8) * (M_PI / 4);
        for (int a = 1; a < n; a++)   /* sort */
            for (int b = a; b > 0 && ang[b] < ang[b - 1]; b--) { const double s = ang[b]; ang[b] = ang[b - 1]; ang[b - 1] = s; }
        int64_t qx[MAXN], qy[MAXN];
        for (int k = 0; k < n; k++) {
            const double rad = 16.0 * (1 + mc_rng_below(&r, 30));
            qx[k] = cx + (int64_t)llround(rad * cos(ang[k]));
            qy[k] = cy + (int64_t)llround(rad * sin(ang[k]));
            if (mc_rng_below(&r, 2)) { qx[k] = qx[k] / 8 * 8; qy[k] = qy[k] / 8 * 8; }
        }
        /* a simple fan: every triangle (c, q_k, q_k+1) turns the same way, one turn in all */
        int ok = 1;
        double turn = 0;
        for (int k = 0; k < n && ok; k++) {
            const int k1 = (k + 1) % n;
            ok = cross64(cx, cy, qx[k], qy[k], qx[k1], qy[k1]) > 0;
            double d = atan2((double)(qy[k1] - cy), (double)(qx[k1] - cx)) - atan2((double)(qy[k] - cy), (double)(qx[k] - cx));
            while (d < 0) d += 2 * M_PI;
            turn += d;
        }
        if (!ok || fabs(turn - 2 * M_PI) > 1e-6) continue;
        memset(cnt, 0, g.n * sizeof *cnt);
        for (int k = 0; k < n; k++) {
            const int k1 = (k + 1) % n;
            mc_raster_vertex v[3] = {{(int32_t)cx, (int32_t)cy, 5}, {(int32_t)qx[k], (int32_t)qy[k], 9},
                                     {(int32_t)qx[k1], (int32_t)qy[k1], 1}};
            const int rot = (int)mc_rng_below(&r, 3);   /* any corner first */
            const mc_raster_vertex u[3] = {v[rot], v[(rot + 1) % 3], v[(rot + 2) % 3]};
            accumulate(&g, u, cnt);
        }
        for (unsigned i = 0; i < g.n; i++) {
            const int64_t px = 16 * (int64_t)(i % w) + 8, py = 16 * (int64_t)(i / w) + 8;
            /* strictly inside the fan's polygon: in a closed triangle, off its outer edge; outside:
             * in no closed triangle */
            int inside = 0, touch = 0;
            for (int k = 0; k < n; k++) {
                const int k1 = (k + 1) % n;
                const int64_t e0 = cross64(cx, cy, qx[k], qy[k], px, py), e1 = cross64(qx[k], qy[k], qx[k1], qy[k1], px, py);
                const int64_t e2 = cross64(qx[k1], qy[k1], cx, cy, px, py);
                if (e0 >= 0 && e1 >= 0 && e2 >= 0) { touch = 1; if (e1 > 0) inside = 1; }
            }
            if (cnt[i] > 1 || (inside && cnt[i] != 1) || (!touch && cnt[i] != 0))
                fail_msg("fan %d around (%ld, %ld), %d spokes: pixel (%u, %u) covered %u times (inside %d)", done,
                         (long)cx, (long)cy, n, i % w, i / w, cnt[i], inside);
        }
        done++;
    }
    free(cnt);
    gt_free(&g);
}

/* Triangles of a few pixels with every corner on, or one subpixel beside, a pixel centre or a pixel
 * edge: the bounding-box tests that reject a triangle before any setup (no centre in its box that
 * the top-left rule can let it cover: corners and horizontal edges exactly on centres), against the
 * reference; partly off the target on each side, culled and not. */
static void test_small_boxes(void **state)
{
    (void)state;
    static const int32_t c[] = {7, 8, 9, 15, 16, 17, 23, 24, 25, 40};
    enum { N = sizeof c / sizeof c[0], P = N * N };
    gtarget g = gt_new(2, 2);
    mc_rng r;
    mc_rng_seed(&r, 61, 3);
    unsigned long drawn = 0;
    for (int a = 0; a < P; a++)
        for (int b = a + 1; b < P; b++)
            for (int k = b + 1; k < P; k++) {
                /* shifted a pixel left, up, both or not: the target clips each side */
                const int32_t ox = (a + b + k) % 2 ? -16 : 0, oy = (a + b + k) % 4 >= 2 ? -16 : 0;
                const mc_raster_vertex v[3] = {{c[a % N] + ox, c[a / N] + oy, 100 + mc_rng_below(&r, 400)},
                                               {c[b % N] + ox, c[b / N] + oy, 100 + mc_rng_below(&r, 400)},
                                               {c[k % N] + ox, c[k / N] + oy, 100 + mc_rng_below(&r, 400)}};
                check_against_ref(&g, v, (a ^ b ^ k) & 1 ? MC_RASTER_CULL_BACK : 0u);
                for (unsigned i = 0; i < g.n; i++) drawn += g.t.depth[i] != MC_DEPTH_EMPTY;
                const mc_raster_vertex u[3] = {v[0], v[2], v[1]};   /* the other orientation */
                check_against_ref(&g, u, 0);
            }
    assert_true(drawn > 1000);
    gt_free(&g);
}

static void test_culling(void **state)
{
    (void)state;
    gtarget g = gt_new(16, 16);
    /* right, then down the screen: clockwise as seen (y down), a back face */
    const mc_raster_vertex back[3] = {{8, 8, 10}, {8 + 160, 8, 10}, {8, 8 + 160, 10}};
    const mc_raster_vertex front[3] = {back[0], back[2], back[1]};
    assert_int_equal(draw(&g, back, 1, MC_RASTER_CULL_BACK), 0);
    for (unsigned i = 0; i < g.n; i++) assert_int_equal(g.t.depth[i], MC_DEPTH_EMPTY);
    const uint32_t n = draw(&g, front, 1, MC_RASTER_CULL_BACK);
    assert_true(n > 0);
    mc_clear(&g.t);
    assert_int_equal(draw(&g, back, 1, 0), n);   /* both orientations without the flag */
    mc_clear(&g.t);
    assert_int_equal(draw(&g, front, 1, 0), n);
    /* random triangles: drawn with the flag exactly when (x1-x0)(y2-y0) - (x2-x0)(y1-y0) < 0 */
    mc_rng r;
    mc_rng_seed(&r, 41, 1);
    for (int it = 0; it < 5000; it++) {
        mc_raster_vertex v[3];
        random_triangle(&r, 16, 16, v);
        const int64_t s = (int64_t)(v[1].x - v[0].x) * (v[2].y - v[0].y) - (int64_t)(v[2].x - v[0].x) * (v[1].y - v[0].y);
        mc_clear(&g.t);
        const uint32_t both = draw(&g, v, 1, 0);
        mc_clear(&g.t);
        const uint32_t culled = draw(&g, v, 1, MC_RASTER_CULL_BACK);
        assert_int_equal(culled, s < 0 ? both : 0);
        if (s >= 0)
            for (unsigned i = 0; i < g.n; i++) assert_int_equal(g.t.depth[i], MC_DEPTH_EMPTY);
    }
    gt_free(&g);
}

static void test_depth_test(void **state)
{
    (void)state;
    const unsigned w = 40, h = 30;
    gtarget g = gt_new(w, h);
    gtarget s = gt_new(w, h);
    /* one plane at depth 1000 over the whole target */
    const mc_raster_vertex floor_[3] = {{-16000, -16000, 1000}, {48000, -16000, 1000}, {-16000, 48000, 1000}};
    const mc_raster_vertex tri[3] = {{20, 30, 0}, {600, 100, 0}, {200, 460, 0}};
    for (uint32_t z = 998; z <= 1002; z++) {
        mc_clear(&g.t);
        assert_int_equal(draw(&g, floor_, 1, 0), w * h);
        mc_raster_vertex v[3] = {tri[0], tri[1], tri[2]};
        v[0].z = v[1].z = v[2].z = z;
        mc_clear(&s.t);
        const uint32_t n = draw(&s, v, 2, 0);
        assert_true(n > 0);
        assert_int_equal(draw(&g, v, 2, 0), n);   /* counted before the depth test */
        for (unsigned i = 0; i < g.n; i++) {
            const int in = s.t.depth[i] != MC_DEPTH_EMPTY, wins = in && z < 1000;
            assert_int_equal(g.t.depth[i], wins ? z : 1000);
            assert_int_equal(g.t.color[i], wins ? 2 : 1);
        }
    }
    /* a sloped triangle through the plane: each pixel keeps the nearer, the old one on a tie */
    mc_rng r;
    mc_rng_seed(&r, 51, 2);
    for (int it = 0; it < 500; it++) {
        mc_raster_vertex v[3];
        random_triangle(&r, w, h, v);
        const uint32_t base = 900 + mc_rng_below(&r, 200);
        for (int k = 0; k < 3; k++) v[k].z = base - 100 + mc_rng_below(&r, 201);
        mc_raster_vertex f[3] = {floor_[0], floor_[1], floor_[2]};
        f[0].z = f[1].z = f[2].z = base;
        mc_clear(&g.t);
        draw(&g, f, 1, 0);
        mc_clear(&s.t);
        const uint32_t n = draw(&s, v, 2, 0);
        assert_int_equal(draw(&g, v, 2, 0), n);
        for (unsigned i = 0; i < g.n; i++) {
            const int wins = s.t.depth[i] < base;   /* MC_DEPTH_EMPTY never wins */
            assert_int_equal(g.t.depth[i], wins ? s.t.depth[i] : base);
            assert_int_equal(g.t.color[i], wins ? 2 : 1);
        }
    }
    gt_free(&g);
    gt_free(&s);
}

/* mc_raster_slope against the plane's gradient in doubles: floor(max(|dz/dx|, |dz/dy|)) + 1 per
 * pixel, 0 for no area (exact but for a quotient within 1e-9 of an integer, not counted) */
static void test_slope(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 0x5107e, 4);
    for (int i = 0; i < 300000; i++) {
        mc_raster_vertex v[3];
        const int32_t spread = i % 3 == 0 ? 40 : i % 3 == 1 ? 4000 : 1 << 21;
        for (int k = 0; k < 3; k++) {
            v[k].x = (int32_t)mc_rng_below(&r, 2u * (uint32_t)spread + 1u) - spread;
            v[k].y = (int32_t)mc_rng_below(&r, 2u * (uint32_t)spread + 1u) - spread;
            v[k].z = mc_rng_below(&r, MC_DEPTH_EMPTY - 1u);
        }
        if (i % 50 == 0) v[2].x = v[0].x + 2 * (v[1].x - v[0].x), v[2].y = v[0].y + 2 * (v[1].y - v[0].y);   /* no area */
        const double a = (double)(v[1].x - v[0].x) * (v[2].y - v[0].y) - (double)(v[2].x - v[0].x) * (v[1].y - v[0].y);
        const uint64_t got = mc_raster_slope(v);
        if (a == 0) {
            assert_int_equal(got, 0);
            continue;
        }
        const double z1 = (double)v[1].z - v[0].z, z2 = (double)v[2].z - v[0].z;
        const double gx = fabs(z1 * (v[2].y - v[0].y) - z2 * (v[1].y - v[0].y)) * 16 / fabs(a);
        const double gy = fabs((double)(v[1].x - v[0].x) * z2 - (double)(v[2].x - v[0].x) * z1) * 16 / fabs(a);
        const double g = gx > gy ? gx : gy;
        if (fabs(g - floor(g + 0.5)) < 1e-9 * (g + 1)) continue;
        if ((double)got != floor(g) + 1) fail_msg("triangle %d: slope %llu, reference %.6f", i, (unsigned long long)got, g);
    }
}

static void test_limits(void **state)
{
    (void)state;
    gtarget g = gt_new(320, 240);
    /* corners at the limits: accepted, compared with the reference */
    const mc_raster_vertex big[3] = {{-L, L, 0}, {L, L, ZTOP}, {0, -L, 30000}};
    check_against_ref(&g, big, 0);
    assert_int_equal(mc_raster_triangle(&g.t, big, 7, 0), 320 * 240);
    const mc_raster_vertex corners[3] = {{-L, -L, 5}, {L, -L, 60000}, {L, L, 77}};
    check_against_ref(&g, corners, 0);
    const mc_raster_vertex thin[3] = {{-L, -L, 5}, {L, L, 60000}, {L, L - 1, 77}};
    check_against_ref(&g, thin, 0);
    /* one step beyond, on any coordinate of any corner: nothing drawn */
    for (int k = 0; k < 3; k++) {
        for (int c = 0; c < 4; c++) {
            mc_raster_vertex v[3] = {big[0], big[1], big[2]};
            int32_t *p = c & 1 ? &v[k].y : &v[k].x;
            *p = c & 2 ? L + 1 : -L - 1;
            mc_clear(&g.t);
            assert_int_equal(draw(&g, v, 7, 0), 0);
            for (unsigned i = 0; i < g.n; i++) assert_int_equal(g.t.depth[i], MC_DEPTH_EMPTY);
            *p = c & 2 ? INT32_MAX : INT32_MIN;
            assert_int_equal(draw(&g, v, 7, 0), 0);
        }
    }
    /* degenerate: collinear, repeated corners, one point */
    const mc_raster_vertex deg[4][3] = {{{8, 8, 1}, {168, 88, 1}, {328, 168, 1}},
                                        {{8, 8, 1}, {8, 8, 1}, {800, 900, 1}},
                                        {{-L, -L, 1}, {L, L, 1}, {0, 0, 1}},
                                        {{24, 24, 1}, {24, 24, 1}, {24, 24, 1}}};
    for (int k = 0; k < 4; k++) {
        mc_clear(&g.t);
        assert_int_equal(draw(&g, deg[k], 7, 0), 0);
        for (unsigned i = 0; i < g.n; i++) assert_int_equal(g.t.depth[i], MC_DEPTH_EMPTY);
    }
    /* z beyond the largest drawable depth is clamped below MC_DEPTH_EMPTY - 1 */
    const mc_raster_vertex far_[3] = {{0, 0, 0xFFFFFFFFu}, {5120, 0, 0xFFFFu}, {0, 3840, 0xFFFEu}};
    mc_clear(&g.t);
    assert_true(draw(&g, far_, 7, 0) > 0);
    for (unsigned i = 0; i < g.n; i++) assert_true(g.t.depth[i] == MC_DEPTH_EMPTY || g.t.depth[i] == ZTOP);
    /* an empty target */
    mc_target none = {g.t.color, g.t.depth, 0, 5};
    assert_int_equal(mc_raster_triangle(&none, big, 7, 0), 0);
    gt_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_slope),
        cmocka_unit_test(test_random_1x1),
        cmocka_unit_test(test_random_7x5),
        cmocka_unit_test(test_random_33x17),
        cmocka_unit_test(test_random_320x240),
        cmocka_unit_test(test_random_65535x1),
        cmocka_unit_test(test_random_1x65535),
        cmocka_unit_test(test_tiling_rectangles),
        cmocka_unit_test(test_tiling_fans),
        cmocka_unit_test(test_small_boxes),
        cmocka_unit_test(test_culling),
        cmocka_unit_test(test_depth_test),
        cmocka_unit_test(test_limits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
