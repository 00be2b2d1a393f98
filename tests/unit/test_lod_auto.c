/* The host viewer's automatic level of detail (runtime/front/host/lod_auto.h):
 *   - the plan: the level kept before a frame has been measured after the first, and while the
 *     level's time is within the trigger; otherwise the budget of the power-law fit, exactly;
 *     learning started anew when the style drawn changes, kept while it does not;
 *   - the exponent learned from two levels' times of an exact power law, halving its distance each
 *     change (EMA weight 1/2 from 1);
 *   - closed loop, against a plant made after bunny00's line drawings at 320x240 (make
 *     bench-lod-auto): a frame takes 0.75 ms (F / 20,000)^0.4 for F faces, times a turn's drift of
 *     +-6 % and noise of +-2 %; a level change costs 10 us a split or collapse when under a 48th of
 *     the faces change (the crease bits brought over) and 0.15 us a face of the new level otherwise
 *     (recomputed); the level is the finest whose faces (2 a vertex) fit the budget. Held: frames
 *     after the first 20 whose frame and change together are within 10 % of the target: at least
 *     95 % of 280 frames, at three targets and four seeds.
 * PCG32 with fixed seeds: runs are deterministic.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <modelc/rng.h>
#include "../../runtime/front/host/lod_auto.h"

static void test_plan(void **state)
{
    (void)state;
    mc_host_lod_auto a;
    mc_host_lod_auto_init(&a, 2.0);
    assert_int_equal(mc_host_lod_auto_plan(&a, 1000).move, 0);   /* nothing measured */
    mc_host_lod_auto_frame(&a, 1000, 9.0);                      /* the first frame: not learned */
    assert_int_equal(mc_host_lod_auto_plan(&a, 1000).move, 0);
    mc_host_lod_auto_frame(&a, 1000, 2.0 * (1 + MC_HOST_LOD_TRIGGER * 0.9));
    assert_int_equal(mc_host_lod_auto_plan(&a, 1000).move, 0);   /* within the trigger */
    assert_int_equal(mc_host_lod_auto_plan(&a, 1200).move, 0);   /* another level than the one timed */
    mc_host_lod_auto_init(&a, 2.0);
    mc_host_lod_auto_style(&a, 1);
    mc_host_lod_auto_frame(&a, 1000, 1.0);
    mc_host_lod_auto_frame(&a, 1000, 4.0);
    mc_host_lod_plan p = mc_host_lod_auto_plan(&a, 1000);
    assert_int_equal(p.move, 1);
    assert_int_equal(p.max_faces, 500);   /* exponent 1: 1000 * 2 / 4 */
    mc_host_lod_auto_frame(&a, 1000, 4.0 * (1 + MC_HOST_LOD_TRIGGER * 1.5));
    assert_true(mc_host_lod_auto_plan(&a, 1000).move);
    for (int i = 0; i < 8; i++) mc_host_lod_auto_frame(&a, 1000, 1.0);   /* too fast: finer */
    p = mc_host_lod_auto_plan(&a, 1000);
    assert_int_equal(p.move, 1);
    assert_true(p.max_faces > 1000);
    assert_true(fabs(p.max_faces - 1000 * 2.0 / a.level_ms) <= 1);
    /* another style: nothing learned, and its first frame teaches nothing; the same style: kept */
    mc_host_lod_auto_style(&a, 1);
    assert_int_equal(mc_host_lod_auto_plan(&a, 1000).move, 1);
    mc_host_lod_auto_style(&a, 2);
    assert_int_equal(mc_host_lod_auto_plan(&a, 1000).move, 0);
    mc_host_lod_auto_frame(&a, 1000, 9.0);
    assert_int_equal(mc_host_lod_auto_plan(&a, 1000).move, 0);
    mc_host_lod_auto_frame(&a, 1000, 4.0);
    assert_int_equal(mc_host_lod_auto_plan(&a, 1000).move, 1);
    assert_int_equal(mc_host_lod_auto_plan(&a, 1000).max_faces, 500);
    mc_host_lod_auto_style(&a, 2);
    assert_int_equal(mc_host_lod_auto_plan(&a, 1000).max_faces, 500);
}

/* Exact times c F^0.4 at levels moving by a fifth: the exponent from 1 halves its way to 0.4 with
 * every level left (the first level left has none before it). */
static void test_exponent(void **state)
{
    (void)state;
    mc_host_lod_auto a;
    mc_host_lod_auto_init(&a, 1.0);
    mc_host_lod_auto_frame(&a, 5000, 50.0);   /* the first frame */
    double want = 1;
    uint32_t faces = 5000;
    for (int k = 0; k < 8; k++, faces = faces * 4 / 5) {
        for (int i = 0; i < 3; i++) mc_host_lod_auto_frame(&a, faces, 0.02 * pow(faces, 0.4));
        if (k >= 2) want += (0.4 - want) * 0.5;   /* a pair of levels is complete when the next begins */
        assert_true(fabs(a.exponent - want) < 1e-9);
    }
    assert_true(fabs(a.exponent - 0.4) < 0.02);
}

/* The plant (above). Returns the frames held of the 280 after the first 20. */
static int simulate(double target, uint64_t seed)
{
    const uint32_t V0 = 200, V = 37706;
    mc_rng r;
    mc_rng_seed(&r, seed, 1);
    mc_host_lod_auto a;
    mc_host_lod_auto_init(&a, target);
    uint32_t level = V, held = 0;
    for (int i = 0; i < 300; i++) {
        uint32_t faces = 2 * level;
        const mc_host_lod_plan p = mc_host_lod_auto_plan(&a, faces);
        double change = 0;
        if (p.move) {
            uint32_t n = p.max_faces / 2;
            n = n < V0 ? V0 : n > V ? V : n;
            const uint32_t steps = n > level ? n - level : level - n;
            change = 2 * steps > (2 * n) / 48 ? 0.15e-3 * 2 * n : 10e-3 * steps;
            level = n, faces = 2 * level;
        }
        const double drift = 1 + 0.06 * sin(2 * 3.14159265358979 * i / 300);
        const double noise = 1 + 0.02 * ((double)mc_rng_below(&r, 2001) / 1000 - 1);
        const double frame = 0.75 * pow(faces / 20000.0, 0.4) * drift * noise * (i == 0 ? 5 : 1);
        mc_host_lod_auto_frame(&a, faces, frame);
        if (i >= 20) held += fabs(frame + change - target) <= 0.1 * target;
    }
    return (int)held;
}

static void test_closed_loop(void **state)
{
    (void)state;
    const double targets[] = {0.55, 0.65, 0.75};
    for (int k = 0; k < 3; k++) {
        for (uint64_t seed = 1; seed <= 4; seed++) {
            const int held = simulate(targets[k], seed);
            if (held < 266) fail_msg("target %.2f ms seed %u: %d of 280 frames held", targets[k], (unsigned)seed, held);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plan),
        cmocka_unit_test(test_exponent),
        cmocka_unit_test(test_closed_loop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
