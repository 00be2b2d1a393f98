/* Image edges (modelc/imgedge.h) against the double-precision reference (runtime/ref/imgedge_ref.c):
 *   - random frames 1x1 to 70x50 (noise, smooth ramps, discs and half-planes at random angles with
 *     noise, inside a wider buffer so that the stride matters) at random thresholds: every code equal
 *     to the reference's except at candidates whose angle lies within 2^-14 rad of a boundary (which
 *     the test counts and bounds), border pixels 0, the count returned equal to the codes set;
 *   - straight steps: a vertical step gives one column of bin 0, a horizontal one a row of bin 4,
 *     the two diagonals bins 2 and 6, each one pixel thick;
 *   - a flat frame and frames under 3 pixels wide or high have no edges (and out is cleared);
 *     thresholds below 1 act as 1, above the largest magnitude leave nothing;
 *   - mc_imgedge_bin of directions of every length up to the int32 limit against atan2;
 *   - mc_imgedge_masks (codes spread to bin masks over a square of radius 0 .. 3) against a brute-force
 *     search on random code images 1x1 to 40x30, and mc_imgedge_spread on by 0 .. 3 more against the
 *     square of the two radii's sum; mc_imgedge_bin_mask against mc_imgedge_dirs_match;
 *   - mc_imgedge_dirs_match against the distance around the half circle, every pair and tolerance.
 * Random numbers: PCG32 (modelc/rng.h) with fixed seeds.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include <modelc/imgedge.h>
#include <modelc/rng.h>
#include "../../runtime/ref/imgedge_ref.h"

#define PI 3.14159265358979323846

static uint32_t below(mc_rng *r, uint32_t n) { return mc_rng_next(r) % n; }

static uint8_t clamp8(double v) { return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v + 0.5); }

/* A w x h frame in a buffer of stride bytes a row, one of a few kinds of picture. */
static void picture(mc_rng *r, uint8_t *img, unsigned stride, unsigned w, unsigned h)
{
    const unsigned kind = below(r, 4), noise = below(r, 3) * below(r, 20);
    const double a = below(r, 3600) * PI / 1800.0, cx = below(r, w + 1), cy = below(r, h + 1);
    const double rad = 1 + below(r, 30), lo = below(r, 256), hi = below(r, 256), slope = below(r, 40) / 4.0;
    for (unsigned y = 0; y < h; y++)
        for (unsigned x = 0; x < w; x++) {
            double v;
            const double dx = x - cx, dy = y - cy;
            switch (kind) {
            case 0: v = below(r, 256); break;                                          /* noise */
            case 1: v = lo + slope * (dx * cos(a) + dy * sin(a)); break;                /* ramp */
            case 2: v = dx * dx + dy * dy < rad * rad ? hi : lo; break;                 /* disc */
            default: v = dx * cos(a) + dy * sin(a) < 0 ? lo : hi; break;                /* half-plane */
            }
            if (noise) v += (double)below(r, 2 * noise + 1) - noise;
            img[(size_t)y * stride + x] = clamp8(v);
        }
}

static void test_against_reference(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 0x1d6e, 7);
    unsigned long pixels = 0, near_total = 0, edges = 0;
    for (int iter = 0; iter < 3000; iter++) {
        const unsigned w = 1 + below(&r, 70), h = 1 + below(&r, 50), stride = w + below(&r, 5);
        uint8_t *img = malloc((size_t)stride * h), *out = malloc((size_t)w * h), *ref = malloc((size_t)w * h);
        uint8_t *nearby = malloc((size_t)w * h);
        uint32_t *scratch = malloc(4u * MC_IMGEDGE_SCRATCH_WORDS(w));
        assert_non_null(img), assert_non_null(scratch);
        memset(img, 0xEE, (size_t)stride * h);   /* the bytes past each row must not matter */
        picture(&r, img, stride, w, h);
        memset(out, 0x77, (size_t)w * h);
        const unsigned t = below(&r, 8) == 0 ? below(&r, 1500) : 1 + below(&r, 300);
        const uint32_t n = mc_imgedge(img, stride, (uint16_t)w, (uint16_t)h, (uint16_t)t, out, scratch);
        const uint32_t nr = mc_imgedge_ref(img, stride, w, h, t, ldexp(1.0, -14), ref, nearby);
        uint32_t set = 0;
        for (unsigned y = 0; y < h; y++)
            for (unsigned x = 0; x < w; x++) {
                const size_t i = (size_t)y * w + x;
                set += out[i] != 0;
                if (out[i] > MC_IMGEDGE_DIRS) fail_msg("iter %d (%ux%u t %u): code %u at %u,%u", iter, w, h, t, out[i], x, y);
                if ((x == 0 || y == 0 || x + 1 == w || y + 1 == h) && out[i])
                    fail_msg("iter %d: border pixel %u,%u set", iter, x, y);
                if (nearby[i]) { near_total++; continue; }
                if (out[i] != ref[i])
                    fail_msg("iter %d (%ux%u stride %u t %u): pixel %u,%u code %u, reference %u", iter, w, h, stride, t, x,
                             y, out[i], ref[i]);
            }
        assert_int_equal(n, set);
        if (!near_total) assert_int_equal(n, nr);
        pixels += (unsigned long)w * h, edges += n;
        free(img), free(out), free(ref), free(nearby), free(scratch);
    }
    /* the boundary band is 2^-14 rad wide on each side of 12 boundaries: a sliver of the angles */
    assert_true(near_total * 1000 < edges + 1000);
    assert_true(edges > pixels / 50);   /* the pictures do have edges */
}

/* one step of grey levels 40 | 220 across the line through the frame's centre with normal (ix, iy)
 * (integers: a diagonal step is then symmetric about the diagonal, so its Sobel gradient is exactly
 * diagonal) */
static unsigned step_edges(int ix, int iy, unsigned want_bin)
{
    enum { W = 41, H = 41 };
    uint8_t img[W * H], out[W * H];
    uint32_t scratch[MC_IMGEDGE_SCRATCH_WORDS(W)];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) img[y * W + x] = 2 * (ix * (x - 20) + iy * (y - 20)) + 1 < 0 ? 40 : 220;
    const uint32_t n = mc_imgedge(img, W, W, H, 100, out, scratch);
    /* along the step, away from the frame's border: one edge pixel across it, of the bin */
    unsigned lines = 0;
    for (int y = 3; y < H - 3; y++)
        for (int x = 3; x < W - 3; x++) {
            const uint8_t c = out[y * W + x];
            if (!c) continue;
            assert_int_equal(c, 1 + want_bin);
            /* the neighbours across the edge (along the gradient) are not edge pixels */
            assert_int_equal(out[(y + iy) * W + x + ix], 0);
            assert_int_equal(out[(y - iy) * W + x - ix], 0);
            lines++;
        }
    assert_true(n >= lines);
    return lines;
}

static void test_steps(void **state)
{
    (void)state;
    assert_true(step_edges(1, 0, 0) >= 30);    /* vertical edge, horizontal gradient */
    assert_true(step_edges(0, 1, 4) >= 30);    /* horizontal edge */
    assert_true(step_edges(1, 1, 2) >= 30);
    assert_true(step_edges(-1, 1, 6) >= 30);
    assert_true(step_edges(-1, 0, 0) >= 30);   /* the other polarity: the same orientation */
    assert_true(step_edges(0, -1, 4) >= 30);
    assert_true(step_edges(1, -1, 6) >= 30);
}

static void test_flat_and_small(void **state)
{
    (void)state;
    uint8_t img[64 * 64], out[64 * 64];
    uint32_t scratch[MC_IMGEDGE_SCRATCH_WORDS(64)];
    memset(img, 123, sizeof img);
    memset(out, 9, sizeof out);
    assert_int_equal(mc_imgedge(img, 64, 64, 64, 1, out, scratch), 0);
    for (size_t i = 0; i < sizeof out; i++) assert_int_equal(out[i], 0);
    for (unsigned w = 1; w <= 4; w++)
        for (unsigned h = 1; h <= 4; h++) {
            if (w >= 3 && h >= 3) continue;
            for (unsigned i = 0; i < w * h; i++) img[i] = (uint8_t)(i * 97), out[i] = 9;
            assert_int_equal(mc_imgedge(img, w, (uint16_t)w, (uint16_t)h, 1, out, scratch), 0);
            for (unsigned i = 0; i < w * h; i++) assert_int_equal(out[i], 0);
        }
    /* a checkerboard: the largest gradients there are; threshold 0 acts as 1, 1442 leaves none */
    for (unsigned y = 0; y < 64; y++)
        for (unsigned x = 0; x < 64; x++) img[y * 64 + x] = ((x / 4 + y / 4) & 1) ? 255 : 0;
    const uint32_t n0 = mc_imgedge(img, 64, 64, 64, 0, out, scratch);
    assert_true(n0 > 0);
    assert_int_equal(mc_imgedge(img, 64, 64, 64, 1, out, scratch), n0);
    assert_int_equal(mc_imgedge(img, 64, 64, 64, MC_IMGEDGE_THRESHOLD_MAX, out, scratch), 0);
    assert_int_equal(mc_imgedge(img, 64, 64, 64, 60000, out, scratch), 0);
}

/* mc_imgedge_bin of directions of any length against atan2, away from the boundaries */
static void test_bin(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 0xb1, 3);
    unsigned near = 0;
    for (int i = 0; i < 1000000; i++) {
        const int shift = (int)below(&r, 31);
        int32_t gx = (int32_t)(mc_rng_next(&r) >> shift), gy = (int32_t)(mc_rng_next(&r) >> shift);
        if (below(&r, 2)) gx = -gx;
        if (below(&r, 2)) gy = -gy;
        if (i < 8) gx = (i & 1) ? INT32_MAX : -INT32_MAX, gy = (i & 2) ? INT32_MAX : 0;
        if (!gx && !gy) continue;
        double a = fmod(atan2(gy, gx) * 180.0 / PI + 360.0, 180.0);
        double gap = fmod(a - 11.25, 22.5);
        if (gap < 0) gap += 22.5;
        if (gap < 1e-3 || 22.5 - gap < 1e-3) { near++; continue; }
        const unsigned want = (unsigned)floor((a + 11.25) / 22.5) % 8;
        if (mc_imgedge_bin(gx, gy) != want) fail_msg("(%d, %d): bin %u, angle %.6f: %u", gx, gy, mc_imgedge_bin(gx, gy), a, want);
    }
    assert_true(near < 1000);
}

/* mc_imgedge_masks against a brute-force square of each radius; mc_imgedge_bin_mask against
 * mc_imgedge_dirs_match */
static void test_masks(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 0x3a5c, 4);
    for (int iter = 0; iter < 3000; iter++) {
        const unsigned w = 1 + below(&r, 40), h = 1 + below(&r, 30), radius = below(&r, 4);   /* w: 5 words and a part */
        uint8_t *codes = malloc(w * h), *m = malloc(w * h), *scratch = malloc(MC_IMGEDGE_MASK_SCRATCH(w, radius));
        const unsigned density = 1 + below(&r, 20);
        for (unsigned i = 0; i < w * h; i++) codes[i] = below(&r, density) ? 0 : (uint8_t)(1 + below(&r, 8)), m[i] = codes[i];
        mc_imgedge_masks(m, (uint16_t)w, (uint16_t)h, radius, scratch);
        for (unsigned y = 0; y < h; y++)
            for (unsigned x = 0; x < w; x++) {
                unsigned want = 0;
                for (unsigned yy = 0; yy < h; yy++)
                    for (unsigned xx = 0; xx < w; xx++)
                        if (codes[yy * w + xx] && abs((int)xx - (int)x) <= (int)radius && abs((int)yy - (int)y) <= (int)radius)
                            want |= 1u << (codes[yy * w + xx] - 1u);
                if (m[y * w + x] != want) fail_msg("iter %d (%ux%u radius %u): pixel %u,%u mask %02x, want %02x", iter, w, h, radius, x, y, m[y * w + x], want);
            }
        /* spread on by r2: the codes spread by radius + r2 */
        const unsigned r2 = below(&r, 4);
        uint8_t *s2 = malloc(MC_IMGEDGE_MASK_SCRATCH(w, r2));
        mc_imgedge_spread(m, (uint16_t)w, (uint16_t)h, r2, s2);
        const int rr = (int)(radius + r2);
        for (unsigned y = 0; y < h; y++)
            for (unsigned x = 0; x < w; x++) {
                unsigned want = 0;
                for (unsigned yy = 0; yy < h; yy++)
                    for (unsigned xx = 0; xx < w; xx++)
                        if (codes[yy * w + xx] && abs((int)xx - (int)x) <= rr && abs((int)yy - (int)y) <= rr)
                            want |= 1u << (codes[yy * w + xx] - 1u);
                if (m[y * w + x] != want) fail_msg("iter %d (%ux%u radius %u then %u): pixel %u,%u mask %02x, want %02x", iter, w, h, radius, r2, x, y, m[y * w + x], want);
            }
        free(codes), free(m), free(scratch), free(s2);
    }
    for (unsigned bin = 0; bin < MC_IMGEDGE_DIRS; bin++)
        for (unsigned t = 0; t <= MC_IMGEDGE_DIRS; t++)
            for (unsigned b = 0; b < MC_IMGEDGE_DIRS; b++)
                assert_int_equal((mc_imgedge_bin_mask(bin, t) >> b) & 1u, mc_imgedge_dirs_match(b, bin, t));
}

static void test_dirs_match(void **state)
{
    (void)state;
    for (unsigned a = 0; a < MC_IMGEDGE_DIRS; a++)
        for (unsigned b = 0; b < MC_IMGEDGE_DIRS; b++)
            for (unsigned t = 0; t <= MC_IMGEDGE_DIRS; t++) {
                int d = abs((int)a - (int)b);
                if (MC_IMGEDGE_DIRS - d < d) d = MC_IMGEDGE_DIRS - d;
                assert_int_equal(mc_imgedge_dirs_match(a, b, t), d <= (int)t);
            }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_against_reference),
        cmocka_unit_test(test_steps),
        cmocka_unit_test(test_flat_and_small),
        cmocka_unit_test(test_bin),
        cmocka_unit_test(test_masks),
        cmocka_unit_test(test_dirs_match),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
