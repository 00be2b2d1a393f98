/* The re-detection search (modelc/detect.h), on the synthetic cube scene (tests/track/cube_scene.h):
 *   - mc_detect_shift's shift and count equal a brute-force search written from the promise: the
 *     pose's visible line pixels read pixel by pixel (mc_sdepth_in_use, row-major), every
 *     ceil(n / 64)-th taken, each shift of the coarse grid counted, the first best refined over the
 *     shifts within stride - 1 of it; for poses shifted by various amounts, strides 1..5, reaches;
 *   - with the frame's edges moved by a shift, it finds the shift (within the masks' one-pixel
 *     spread) with every feature matched;
 *   - a pose with nothing on the frame gives 0 and no shift;
 *   - mc_detect_move against the pinhole formula in doubles, and in place (out = t) the same.
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

#include <modelc/detect.h>
#include <modelc/imgedge.h>
#include "../track/cube_scene.h"

typedef struct ref_feature {
    int x, y;
    uint8_t want;
} ref_feature;

/* the features as the promise has them, from the buffer the last score left */
static int ref_features(const cube_scene *s, ref_feature *f)
{
    int n = 0, k = 0;
    for (unsigned y = 0; y < s->h; y++)
        for (unsigned x = 0; x < s->w; x++) n += mc_sdepth_in_use(&s->sd, x, y);
    if (!n) return 0;
    const int step = (n + MC_DETECT_FEATURES - 1) / MC_DETECT_FEATURES;
    int seen = 0;
    for (unsigned y = 0; y < s->h; y++)
        for (unsigned x = 0; x < s->w; x++) {
            if (!mc_sdepth_in_use(&s->sd, x, y)) continue;
            if (seen++ % step == 0 && k < MC_DETECT_FEATURES) {
                f[k].x = (int)x, f[k].y = (int)y;
                f[k].want = mc_imgedge_bin_mask((unsigned)(s->color[y * s->w + x] - 1) & 7u, s->view.tolerance);
                k++;
            }
        }
    return k;
}

static int ref_count(const cube_scene *s, const ref_feature *f, int n, int dx, int dy)
{
    int c = 0;
    for (int i = 0; i < n; i++) {
        const int x = f[i].x + dx, y = f[i].y + dy;
        if (x < 0 || y < 0 || x >= (int)s->w || y >= (int)s->h) continue;
        c += (s->masks[y * (int)s->w + x] & f[i].want) != 0;
    }
    return c;
}

static int ref_best(const cube_scene *s, const ref_feature *f, int n, int cx, int cy, int r, int step, int *bx, int *by)
{
    int best = 0;
    *bx = cx, *by = cy;
    for (int j = -r; j <= r; j++)
        for (int i = -r; i <= r; i++) {
            const int c = ref_count(s, f, n, cx + i * step, cy + j * step);
            if (c > best) best = c, *bx = cx + i * step, *by = cy + j * step;
        }
    return best;
}

/* the truth of frame k moved on the screen by about (sx, sy) pixels */
static void moved_pose(const cube_scene *s, int k, int sx, int sy, int32_t q[4], int32_t t[3])
{
    int32_t t0[3];
    cube_scene_truth(k, q, t0);
    mc_detect_move(&s->cam, t0, sx, sy, t);
}

static void test_against_brute_force(void **state)
{
    (void)state;
    cube_scene *s = malloc(sizeof *s);
    assert_int_equal(cube_scene_new(s, 320, 180), 0);
    static const int moves[][2] = {{0, 0}, {13, -7}, {-30, 22}, {2, 1}, {-45, -40}, {61, 3}};
    int cases = 0;
    for (int k = 0; k <= 40; k += 20) {
        int32_t q[4], t[3];
        cube_scene_truth(k, q, t);
        assert_int_equal(cube_scene_frame(s, q, t), 0);
        for (size_t m = 0; m < sizeof moves / sizeof moves[0]; m++)
            for (int stride = 1; stride <= 5; stride++) {
                const int reach = stride == 1 ? 20 : 64;
                int32_t qm[4], tm[3];
                moved_pose(s, k, moves[m][0], moves[m][1], qm, tm);
                mc_pose pose;
                assert_int_equal(mc_pose_set(&pose, qm, tm), MC_OK);
                int32_t dx = 99, dy = 99;
                const uint32_t got = mc_detect_shift(&s->view, &pose, reach, stride, &dx, &dy);
                /* the reference reads the buffer the search's own score left */
                ref_feature f[MC_DETECT_FEATURES];
                const int n = ref_features(s, f);
                assert_true(n > 20);
                int cx, cy, rx, ry;
                ref_best(s, f, n, 0, 0, reach / stride, stride, &cx, &cy);
                const int want = ref_best(s, f, n, cx, cy, stride - 1, 1, &rx, &ry);
                if ((int)got != want || dx != rx || dy != ry)
                    fail_msg("frame %d, move (%d, %d), stride %d: got %u at (%d, %d), reference %d at (%d, %d)", k,
                             moves[m][0], moves[m][1], stride, got, dx, dy, want, rx, ry);
                cases++;
            }
    }
    print_message("# info: %d searches equal the brute-force reference\n", cases);
    cube_scene_free(s);
    free(s);
}

static void test_finds_the_move(void **state)
{
    (void)state;
    cube_scene *s = malloc(sizeof *s);
    assert_int_equal(cube_scene_new(s, 320, 180), 0);
    uint8_t *m0 = malloc(s->w * s->h);
    assert_non_null(m0);
    static const int moves[][2] = {{17, -11}, {-40, 25}, {5, 33}, {-52, -8}, {0, 0}};
    for (int k = 0; k <= 50; k += 25) {
        int32_t q[4], t[3];
        cube_scene_truth(k, q, t);
        assert_int_equal(cube_scene_frame(s, q, t), 0);
        memcpy(m0, s->masks, s->w * s->h);
        for (size_t m = 0; m < sizeof moves / sizeof moves[0]; m++) {
            /* the frame's edges moved by (sx, sy) pixels: the cube at the true pose fits them there */
            const int sx = moves[m][0], sy = moves[m][1];
            for (int y = 0; y < (int)s->h; y++)
                for (int x = 0; x < (int)s->w; x++) {
                    const int x0 = x - sx, y0 = y - sy;
                    s->masks[y * (int)s->w + x] = x0 >= 0 && y0 >= 0 && x0 < (int)s->w && y0 < (int)s->h ? m0[y0 * (int)s->w + x0] : 0;
                }
            mc_pose pose;
            assert_int_equal(mc_pose_set(&pose, q, t), MC_OK);
            int32_t dx, dy;
            const uint32_t got = mc_detect_shift(&s->view, &pose, 64, 3, &dx, &dy);
            ref_feature f[MC_DETECT_FEATURES];
            const int n = ref_features(s, f);
            /* every feature matches there; the masks' one-pixel spread may let a neighbour match all too */
            if (abs(dx - sx) > 1 || abs(dy - sy) > 1 || (int)got != n)
                fail_msg("frame %d, edges moved by (%d, %d): found (%d, %d), %u of %d features", k, sx, sy, dx, dy, got, n);
        }
    }
    free(m0);
    cube_scene_free(s);
    free(s);
}

static void test_nothing_on_the_frame(void **state)
{
    (void)state;
    cube_scene *s = malloc(sizeof *s);
    assert_int_equal(cube_scene_new(s, 320, 180), 0);
    int32_t q[4], t[3];
    cube_scene_truth(0, q, t);
    assert_int_equal(cube_scene_frame(s, q, t), 0);
    t[0] += 2000000;   /* 2 m to the side */
    mc_pose pose;
    assert_int_equal(mc_pose_set(&pose, q, t), MC_OK);
    int32_t dx = 5, dy = 5;
    assert_int_equal(mc_detect_shift(&s->view, &pose, 64, 3, &dx, &dy), 0);
    assert_int_equal(dx, 0);
    assert_int_equal(dy, 0);
    cube_scene_free(s);
    free(s);
}

static void test_move(void **state)
{
    (void)state;
    cube_scene *s = malloc(sizeof *s);
    assert_int_equal(cube_scene_new(s, 640, 480), 0);
    const double px = s->cam.px / 65536.0, py = s->cam.py / 65536.0;
    for (int z = 20000; z < 20000000; z = z * 3 + 7)
        for (int d = -300; d <= 300; d += 37) {
            const int32_t t[3] = {-123456 + d, 98765, z};
            int32_t out[3];
            mc_detect_move(&s->cam, t, d, -d / 2, out);
            const double ex = t[0] + d * (double)z / px, ey = t[1] + (-d / 2) * (double)z / py;
            if (fabs(out[0] - ex) > 1 || fabs(out[1] - ey) > 1 || out[2] != z)
                fail_msg("z %d, shift %d: (%d, %d, %d), exact (%.1f, %.1f)", z, d, out[0], out[1], out[2], ex, ey);
            int32_t in_place[3] = {t[0], t[1], t[2]};   /* out may be t (the particle filter's use) */
            mc_detect_move(&s->cam, in_place, d, -d / 2, in_place);
            if (in_place[0] != out[0] || in_place[1] != out[1] || in_place[2] != out[2])
                fail_msg("z %d, shift %d: in place (%d, %d, %d), apart (%d, %d, %d)", z, d, in_place[0], in_place[1],
                         in_place[2], out[0], out[1], out[2]);
        }
    cube_scene_free(s);
    free(s);
}

int main(void)
{
    (void)cube_scene_params, (void)cube_scene_distance, (void)cube_scene_angle;   /* the scene's, unused here */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_against_brute_force),
        cmocka_unit_test(test_finds_the_move),
        cmocka_unit_test(test_nothing_on_the_frame),
        cmocka_unit_test(test_move),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
