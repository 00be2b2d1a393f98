/* Numerical stress: random views of one baked model.
 *
 *   stress N [SEED]      renders N random views; prints one "ok - ..." / "not ok - ...: why" line per
 *                        property and a summary line "# views ... seconds ..."
 *
 * Linked with one model's generated files and a runtime compiled with MC_PLOT_HOOK pointing at
 * record_point below (see tests/stress/suite.sh; the hook tests/render/ uses too, so that the two
 * suites share the runtime's objects), so every point mc_octree_render puts on screen is
 * recorded with its Q F position and the address of its palette index (which names the leaf).
 *
 * Views: every angle (mostly one turn, sometimes any int32), zoom log-uniform over [1/64, 64] and
 * sometimes beyond (0, negative, INT32_MAX: clamped), translations from none to far off screen (up
 * to +-INT32_MAX: clamped to +-MC_COORD_LIMIT/4), orthographic and perspective with the eye anywhere
 * from 1/16 to 256 cube sides (so also inside the model's bounding sphere, with part of the model
 * behind the eye), and out-of-range eyes and projections; every splat (one pixel, zoom footprints,
 * default, out of range); targets from 1x1 to 400x300 (at most MC_TARGET_MAX), sometimes one pixel
 * thin; the model's depth D a quarter of the time, else any of 1..D-1; sometimes an abort callback
 * that gives up after a random number of polls; sometimes a second render on top of the first
 * without clearing. Per frame:
 *
 *  1. guard zones: GUARD elements before and after the colour and the depth buffer hold a pattern
 *     that changes every frame; after mc_clear, after mc_octree_render and after each finishing mode
 *     (mc_finish with every mc_fill) the zones must be unchanged;
 *  2. every point mc_octree_render draws is a leaf the reference (runtime/ref, mc_ref_points, double
 *     precision, the same clamped view) walks, in the same order, and lies within BOUND of the
 *     reference's position on both axes;
 *  3. every leaf the reference puts on screen further than BOUND from the target's edges (and, in
 *     perspective, clearly in front of the near plane) is drawn, unless the frame was aborted;
 *  4. mc_stats.points equals the number of points the hook saw, and mc_octree_render returns MC_OK (or
 *     MC_ERR_SIZE for a target over MC_TARGET_MAX, then writing nothing);
 *  5. with -DSTRESS_ALT=1 (tests/stress/suite.sh links a second copy of octree_render.c built in another
 *     form, STRESS_ALT_FORM: the other depth test, MC_DEPTH_SELECT, and/or the other leaf walk,
 *     MC_LEAF_SWITCH; its entry points renamed mc_octree_render_alt/mc_clear_alt): the other form,
 *     drawing the same frames into a second target, leaves both buffers byte for byte equal to this
 *     one's. The select form parks losing leaves on a spare pixel and puts it back, so a wrong spare
 *     would show here as one changed pixel, which the reference checks cannot see.
 *
 * The bound, per axis, in pixels (S = the clamped zoom times the shorter target side: the cube's
 * screen side; d = drawn depth; F = MC_FRAC_BITS):
 *
 *   Orthographic: a leaf's position is the exact root centre (the screen centre plus an integer
 *   translation, exact in Q F) plus one displacement vector per level 0..d-1. Each vector is rounded
 *   once to Q F from the exact product of the Q30 rotation and the Q16 scale: at most 2^-(F+1) each,
 *   d of them; (d + 1) * 2^-(F+1) leaves half a unit of margin. The rotation itself: each sine table
 *   entry is within 0.5 units of Q30 (2^-31) of the true value; R = Rz (Rx Ry) with each product
 *   rounded to Q30 gives entries within 0.5 (sqrt2 + sqrt2) + 0.5 = 1.92 units for Rx Ry (rows of the
 *   elementary rotations have l1 norm <= sqrt2) and sqrt2 * 1.92 + 0.5 * sqrt3 + 0.5 < 4.1 units for
 *   R, so under 5 * 2^-30 per entry. A leaf lies at sum over levels of (+-1, +-1, +-1) S 2^-(l+2),
 *   so the matrix error moves it by at most 3 * 5 * 2^-30 * S / 2 < S * 2^-27. Hence
 *       B_ortho = (d + 1) * 2^-(F+1) + S * 2^-27            (1.07e-4 px at d = 6, S = 240)
 *   The same bound holds for the depth coordinate z in pixels (perspective keeps z in Q F pixels).
 *
 *   Perspective: the runtime divides per point, q = floor(2^24 eye' / dist') (Q24, truncated: under
 *   2^-24 low), dist' = eye' + z' with eye' the eye distance rounded to Q F (2^-(F+1)) and z' within
 *   B_ortho, then x_s = round(x' q) (2^-(F+1)). With the exact values x, dist, q = eye / dist and
 *   o = x q (the point's offset from the projection centre on screen):
 *       |x' q' - x q| <= |x| 2^-24 + |x| 2^-(F+1) / dist + |o| (B_ortho + 2^-(F+1)) / dist + q B_ortho
 *   to first order (dist shrinks to dist - B_ortho - 2^-(F+1) in the denominators, to cover the
 *   second order), plus 2^-(F+1) for the final rounding. The bound is evaluated per point from the
 *   reference's exact x, dist and o. It grows as the point nears the near plane (1/64 cube side in
 *   front of the eye, where dist is smallest): the division cannot be more exact than the depth it
 *   divides by. A point within that depth error of the near plane may be drawn by one renderer and
 *   not the other; that is allowed, and checked to be the reason.
 *   At drawn depth 3 and more, most perspective leaves come through linear frames (octree_render.c,
 *   config.h MC_LINEAR_ERROR): the node's centre is projected as above and its leaves through the
 *   first-order expansion, whose error pos_linear_ok bounds by MC_LINEAR_ERROR / 256 pixel. The bound
 *   is then twice the one above (evaluated at the leaf, not the centre), plus that error, plus the
 *   frame vectors' rounding (26 half units: three axis steps rounded to 4 units over levels halving
 *   them, and the centre; and 24 half units times the magnification, each step rounded before it is
 *   magnified) and S * 2^-22 for the slope's truncation.
 *
 *   The float build (-DMC_FLOAT=1, config.h) is held to its own format. Its positions are float
 *   sums whose magnitudes stay below M = max(w, h) + |tx| + |ty| + 2 S (+ eye S in perspective), where
 *   floats are spaced at most M 2^-23 apart: each of the d additions and each vector (a few
 *   products, rounded relatively) is off by at most half of that, so with u = M 2^-24 in place of
 *   half a unit of Q F,
 *       B_ortho = (d + 4) u + S * 2^-27
 *   and the perspective bound as above with u, and 2^-22 for the float magnification's relative
 *   error (a division and a product) in place of 2^-24.
 */
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <modelc/app.h>
#include <modelc/modelc.h>
#include "ref.h"

#define MAXW 400
#define MAXH 300
#define GUARD 1024            /* elements before and after each buffer: more than two rows */
#define MAX_PTS (1u << 20)

static uint8_t color_mem[GUARD + MAXW * MAXH + GUARD];
static uint16_t depth_mem[GUARD + MAXW * MAXH + GUARD];
#if STRESS_ALT
/* the other form of the renderer (check 5) */
#ifndef STRESS_ALT_FORM
#define STRESS_ALT_FORM "the branch depth test (MC_DEPTH_SELECT=0)"
#endif
void mc_clear_alt(const mc_target *t);
int mc_octree_render_alt(const mc_octree *octree, const mc_view *view, unsigned depth, const mc_octree_options *opt,
                         const mc_target *t, mc_abort_fn abort, void *user, mc_stats *stats);
static uint8_t alt_color[MAXW * MAXH];
static uint16_t alt_depth[MAXW * MAXH];
#endif

typedef struct fpt { const uint8_t *color; double fx, fy; } fpt;   /* pixels */
static fpt fixed_pts[MAX_PTS];
static size_t n_fixed;
static mc_ref_point ref_pts[MAX_PTS];
static size_t n_ref;

#if MC_FLOAT
void record_point(float fx, float fy, const uint8_t *color)
{
    if (n_fixed < MAX_PTS) fixed_pts[n_fixed] = (fpt){color, fx, fy};
    n_fixed++;
}
#else
void record_point(int32_t fx, int32_t fy, const uint8_t *color)
{
    if (n_fixed < MAX_PTS)
        fixed_pts[n_fixed] = (fpt){color, fx / (double)(1 << MC_FRAC_BITS), fy / (double)(1 << MC_FRAC_BITS)};
    n_fixed++;
}
#endif

static void record_ref(const mc_ref_point *p, void *user)
{
    (void)user;
    if (n_ref < MAX_PTS) ref_pts[n_ref] = *p;
    n_ref++;
}

/* ---- random numbers: xorshift64*, seeded per run ---------------------------------------------- */
static uint64_t rng_state;
static uint64_t rnd(void)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 2685821657736338717ull;
}
static uint32_t rnd_below(uint32_t n) { return (uint32_t)((rnd() >> 32) % n); }
static double rnd_unit(void) { return (double)(rnd() >> 11) / 9007199254740992.0; }
static int32_t rnd_i32(void) { return (int32_t)(uint32_t)(rnd() >> 32); }

/* ---- guard zones ------------------------------------------------------------------------------ */
static uint32_t pattern_seed;
static uint8_t pat8(size_t i) { return (uint8_t)((i * 2654435761u + pattern_seed) >> 13); }
static uint16_t pat16(size_t i) { return (uint16_t)((i * 2246822519u + pattern_seed * 7u) >> 11); }

static void guards_set(size_t n)
{
    for (size_t i = 0; i < GUARD; i++) {
        color_mem[i] = pat8(i);
        depth_mem[i] = pat16(i);
        color_mem[GUARD + n + i] = pat8(GUARD + n + i);
        depth_mem[GUARD + n + i] = pat16(GUARD + n + i);
    }
}

/* index of the first changed guard element, or -1 */
static long guards_check(size_t n)
{
    for (size_t i = 0; i < GUARD; i++) {
        if (color_mem[i] != pat8(i) || depth_mem[i] != pat16(i)) return (long)i;
        size_t j = GUARD + n + i;
        if (color_mem[j] != pat8(j) || depth_mem[j] != pat16(j)) return (long)j;
    }
    return -1;
}

/* ---- abort callback --------------------------------------------------------------------------- */
typedef struct abort_state { uint32_t polls, give_up_after; } abort_state;
static int abort_after(void *user)
{
    abort_state *a = user;
    return ++a->polls > a->give_up_after;
}

/* ---- the checks ------------------------------------------------------------------------------- */
typedef struct counters {
    uint64_t views, frames_drawn, points, points_checked, ref_on_screen, near_plane_disagreements;
    uint64_t aborted, rejected, persp, guard_fail, pos_fail, order_fail, missing_fail, stats_fail, rc_fail;
    uint64_t alt_fail, alt_frames, lod_fail, lod_views, culled_leaves;
    double max_err_ratio;          /* largest |error| / bound seen */
    double max_err_px;             /* largest |error| in pixels, orthographic */
    double max_err_px_persp;       /* largest |error| in pixels, perspective */
} counters;

static char first_failure[512];
static void fail(uint64_t *counter, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void fail(uint64_t *counter, const char *fmt, ...)
{
    (*counter)++;
    if (first_failure[0]) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(first_failure, sizeof first_failure, fmt, ap);
    va_end(ap);
}

static const mc_fill fill_modes[] = {MC_FILL_PIXEL, MC_FILL_SCANLINE};

static void describe(char *buf, size_t n, const mc_view *v, const mc_octree_options *opt, unsigned w, unsigned h,
                     unsigned d, uint64_t view)
{
    snprintf(buf, n,
             "view %" PRIu64 ": %ux%u depth %u yaw %" PRId32 " pitch %" PRId32 " roll %" PRId32 " zoom %" PRId32
             " tx %" PRId32 " ty %" PRId32 " proj %d eye %" PRId32 " splat %d max_error %u",
             view, w, h, d, v->yaw, v->pitch, v->roll, v->zoom, v->tx, v->ty, (int)v->projection, v->eye,
             (int)opt->splat, (unsigned)opt->max_error);
}

/* The level of detail's rule (octree_render.h, mc_octree_lod_depth) in double precision: the least
 * level whose node side on screen is at most max_error / 16 pixels, magnified in perspective by
 * eye / (eye - sqrt(3)/2). The runtime rounds sqrt(3)/2 up to Q16, so [*lo, *hi] spans the levels
 * for the exact radius and that one (equal but at near ties). */
static unsigned lod_rule(const mc_view *cv, unsigned w, unsigned h, unsigned d, unsigned max_error, double radius)
{
    if (!max_error || d <= 1) return d;
    double mag = 1;
    if (cv->projection == MC_PERSPECTIVE) {
        const double eye = cv->eye / 65536.0, dn = eye - radius;
        if (dn < 1.0 / 64) return d;
        mag = eye / dn;
    }
    const double side = cv->zoom / 65536.0 * (w < h ? w : h) * mag;
    for (unsigned l = 1; l < d; l++)
        if (ldexp(side, -(int)l) <= max_error / 16.0) return l;
    return d;
}

static void lod_ref(const mc_view *v, unsigned w, unsigned h, unsigned d, unsigned max_error, unsigned *lo,
                    unsigned *hi)
{
    const mc_view cv = mc_view_clamp(v, w, h);
    const unsigned a = lod_rule(&cv, w, h, d, max_error, sqrt(3) / 2);
    const unsigned b = lod_rule(&cv, w, h, d, max_error, 56756 / 65536.0);
    *lo = a < b ? a : b, *hi = a < b ? b : a;
}

/* 3, with normal cones (octree.h, octree_render.h mc_cull): back[i] = 1 for each leaf i of level d
 * whose level d-3 ancestor's cone faces away from every direction the eye sees the model from, in
 * double precision: a . w < -(s + |a| sin alpha), w the exact view direction (towards the viewer,
 * model axes), sin alpha = (sqrt(3)/2) / eye in perspective (0 orthographic; no cone counts when
 * the eye is inside the sphere). The leaves under each node follow each other in stored order, n3 of
 * them (the record's count). Returns 0 when no cones apply (then nothing may be missing). */
static int back_facing_leaves(const mc_octree *scene, const mc_view *cv, unsigned d, unsigned char *back, size_t n)
{
    memset(back, 0, n);
    if (d < 4 || !scene->levels[d - 3].cones) return 0;
    double r[3][3], spread = 0;
    mc_ref_rotation(cv, r);
    if (cv->projection == MC_PERSPECTIVE) {
        const double eye = cv->eye / 65536.0;
        if (eye <= sqrt(3) / 2) return 0;
        spread = sqrt(3) / 2 / eye;
    }
    size_t leaf = 0;
    for (const mc_chunk *ch = scene->levels[d - 3].cones; ch->data; ch++)
        for (uint32_t o = 0; o + 7 <= ch->size; o += 7) {
            const uint8_t *q = ch->data + o;
            const double a[3] = {(int8_t)q[0], (int8_t)q[1], (int8_t)q[2]};
            const double len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
            const int away = a[0] * r[2][0] + a[1] * r[2][1] + a[2] * r[2][2] < -(q[3] + len * spread);
            const size_t leaves = (size_t)q[5] | (size_t)q[6] << 8;
            for (size_t i = 0; i < leaves && leaf < n; i++) back[leaf++] = (unsigned char)away;
        }
    return 1;
}

static void one_view(const mc_octree *scene, counters *k)
{
    mc_view v = mc_view_default();
    /* angles: mostly one turn, sometimes any int32 */
    v.yaw = rnd_below(8) ? (int32_t)rnd_below(MC_ANGLE_FULL) : rnd_i32();
    v.pitch = rnd_below(8) ? (int32_t)rnd_below(MC_ANGLE_FULL) : rnd_i32();
    v.roll = rnd_below(8) ? (int32_t)rnd_below(MC_ANGLE_FULL) : rnd_i32();
    /* zoom: log-uniform over [1/64, 64], sometimes exactly an end, sometimes out of range */
    switch (rnd_below(32)) {
    case 0: v.zoom = MC_ZOOM_MIN; break;
    case 1: v.zoom = MC_ZOOM_MAX; break;
    case 2: v.zoom = rnd_i32(); break;
    case 3: v.zoom = rnd_below(2) ? INT32_MAX : 0; break;
    default: v.zoom = (int32_t)lround(MC_ZOOM_ONE * exp2(rnd_unit() * 12 - 6)); break;
    }
    /* translations: none, on screen, off screen, far beyond the representable range */
    for (int a = 0; a < 2; a++) {
        int32_t t;
        switch (rnd_below(8)) {
        case 0: t = 0; break;
        case 1: case 2: case 3: t = (int32_t)rnd_below(801) - 400; break;
        case 4: case 5: t = (int32_t)rnd_below(40001) - 20000; break;
        case 6: t = rnd_i32(); break;
        default: t = rnd_below(2) ? INT32_MAX : INT32_MIN; break;
        }
        if (a == 0) v.tx = t; else v.ty = t;
    }
    /* projection and eye: log-uniform over [1/16, 256] sides (inside the bounding sphere below
     * about 0.87, part of the model behind the eye below 0.5), sometimes out of range */
    switch (rnd_below(16)) {
    case 0: v.projection = (mc_projection)(int)rnd_below(7); break;   /* out-of-range enum values too */
    default: v.projection = rnd_below(2) ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC; break;
    }
    switch (rnd_below(16)) {
    case 0: v.eye = rnd_i32(); break;
    case 1: v.eye = MC_EYE_MIN; break;
    default: v.eye = (int32_t)lround(MC_ZOOM_ONE * exp2(rnd_unit() * 12 - 4)); break;
    }
    mc_octree_options opt;
    opt.splat = (mc_splat)(int)rnd_below(4);   /* default, pixel, zoom, and one out of range */
    /* the level of detail: off half the time, else a bound from 1/16 to 64 pixels or the extremes */
    switch (rnd_below(8)) {
    case 0: opt.max_error = 1; break;
    case 1: opt.max_error = 0xFFFF; break;
    case 2: case 3: opt.max_error = (uint16_t)lround(exp2(rnd_unit() * 10)); break;
    default: opt.max_error = 0; break;
    }
    opt.cull = (mc_cull)(int)rnd_below(3);   /* on (default), off, and one out of range (on) */

    unsigned w, h;
    switch (rnd_below(16)) {
    case 0: w = 1 + rnd_below(MAXW); h = 1; break;
    case 1: w = 1; h = 1 + rnd_below(MAXH); break;
    case 2: w = MAXW; h = MAXH; break;
    case 3: case 4: case 5: case 6: case 7: case 8: w = 1 + rnd_below(MAXW); h = 1 + rnd_below(MAXH); break;
    default: w = 1 + rnd_below(MAXW / 2); h = 1 + rnd_below(MAXH / 2); break;
    }
    if (w > MC_TARGET_MAX) w = MC_TARGET_MAX;   /* small at large MC_FRAC_BITS: 8 pixels at F = 24 */
    if (h > MC_TARGET_MAX) h = MC_TARGET_MAX;
    /* the model's depth a quarter of the time, else any shallower one */
    unsigned d = scene->depth < 2 || rnd_below(4) == 0 ? scene->depth : 1 + rnd_below(scene->depth - 1u);
    if (k->views == 0) {   /* the first view frontal, whole, culling: every run sees the cones at work */
        v = mc_view_default();
        opt.cull = MC_CULL_DEFAULT, opt.max_error = 0;
        d = scene->depth;
    }
    size_t n = (size_t)w * h;
    mc_target t = {color_mem + GUARD, depth_mem + GUARD, (uint16_t)w, (uint16_t)h};
    char what[400];
    describe(what, sizeof what, &v, &opt, w, h, d, k->views);
    k->views++;

    pattern_seed = (uint32_t)rnd();
    guards_set(n);
    mc_clear(&t);
    long g = guards_check(n);
    if (g >= 0) fail(&k->guard_fail, "mc_clear changed guard element %ld: %s", g, what);

    /* a target over MC_TARGET_MAX is refused without writing anything (only the size is looked at) */
    if (rnd_below(64) == 0) {
        mc_target big = t;
        if (rnd_below(2)) big.width = (uint16_t)(MC_TARGET_MAX + 1 + rnd_below(100));
        else big.height = (uint16_t)(MC_TARGET_MAX + 1 + rnd_below(100));
        if (mc_octree_render(scene, &v, d, &opt, &big, NULL, NULL, NULL) != MC_ERR_SIZE)
            fail(&k->rc_fail, "a %ux%u target was not refused: %s", big.width, big.height, what);
        k->rejected++;
    }

    abort_state ab = {0, rnd_below(64)};
    int use_abort = rnd_below(8) == 0 && k->views > 1;
    int repeat = rnd_below(16) == 0 ? 2 : 1;   /* sometimes draw twice without clearing */
    mc_stats st = {0, 0, 0, 0, 0};
    for (int r = 0; r < repeat; r++) {
        n_fixed = 0;
        int rc = mc_octree_render(scene, &v, d, &opt, &t, use_abort ? abort_after : NULL, &ab, &st);
        if (rc != MC_OK) fail(&k->rc_fail, "mc_octree_render returned %d: %s", rc, what);
        g = guards_check(n);
        if (g >= 0) fail(&k->guard_fail, "mc_octree_render changed guard element %ld: %s", g, what);
        if (st.points != n_fixed) fail(&k->stats_fail, "stats.points %" PRIu32 " but %zu points plotted: %s", st.points, n_fixed, what);
    }
    /* 6: the level of detail draws the level the double-precision rule picks; the reference then
     * walks that level */
    {
        unsigned lo, hi;
        lod_ref(&v, w, h, d, opt.max_error, &lo, &hi);
        if (st.depth < lo || st.depth > hi)
            fail(&k->lod_fail, "drew depth %" PRIu32 ", the rule gives %u..%u (max_error %u): %s", st.depth, lo, hi,
                 (unsigned)opt.max_error, what);
        k->lod_views += opt.max_error != 0;
        d = st.depth;
    }
    k->frames_drawn += (uint64_t)repeat;
#if STRESS_ALT
    {
        /* 5: the other form of the renderer, the same frames (the same polls, so the same aborts) */
        mc_target at = {alt_color, alt_depth, (uint16_t)w, (uint16_t)h};
        abort_state ab2 = {0, ab.give_up_after};
        mc_clear_alt(&at);
        for (int r = 0; r < repeat; r++)
            mc_octree_render_alt(scene, &v, d, &opt, &at, use_abort ? abort_after : NULL, &ab2, NULL);
        if (memcmp(at.color, t.color, n) || memcmp(at.depth, t.depth, n * sizeof at.depth[0])) {
            size_t p = 0;
            while (p < n && at.color[p] == t.color[p] && at.depth[p] == t.depth[p]) p++;
            fail(&k->alt_fail, STRESS_ALT_FORM " differs at pixel %zu (%zu, %zu): colour %u, depth %u there, %u, %u here: %s", p, p % w, p / w, at.color[p], at.depth[p], t.color[p], t.depth[p], what);
        }
        k->alt_frames++;
    }
#endif
    k->aborted += st.aborted != 0;
    if (n_fixed > MAX_PTS) { fail(&k->order_fail, "more than %u points", MAX_PTS); return; }
    k->points += n_fixed;

    /* the reference, with the same clamped view (mc_ref_points clamps it the same way) */
    mc_view cv = mc_view_clamp(&v, w, h);
    n_ref = 0;
    mc_ref_points(scene, &v, d, w, h, record_ref, NULL);
    if (n_ref > MAX_PTS) { fail(&k->order_fail, "more than %u reference points", MAX_PTS); return; }
    const double S = cv.zoom / 65536.0 * (w < h ? w : h);
    const int persp = cv.projection == MC_PERSPECTIVE;
    const double eye = cv.eye / 65536.0, cx = w / 2.0 + cv.tx, cy = h / 2.0 + cv.ty;
#if MC_FLOAT
    const double m = (w > h ? w : h) + fabs((double)cv.tx) + fabs((double)cv.ty) + 2 * S + (persp ? eye * S : 0);
    const double u = m * ldexp(1, -24);                               /* half the float spacing */
    const double b_ortho = (d + 4) * u + S * ldexp(1, -27);
    const double qrel = ldexp(1, -22);                                /* magnification, relative */
#else
    const double u = ldexp(1, -(MC_FRAC_BITS + 1));                  /* half a unit of Q F */
    const double b_ortho = (d + 1) * u + S * ldexp(1, -27);
    const double qrel = ldexp(1, -24);
#endif
    k->persp += persp;
    /* perspective at d >= 3: linear frames (octree_render.c, config.h MC_LINEAR_ERROR) add their stated
     * error and their vectors' rounding (three levels, three rounded basis terms each, one more for the
     * centre); the centre carries the exact path's errors at a point within the node, hence twice */
    const double lin = persp && d >= 3 && MC_LINEAR_ERROR ? MC_LINEAR_ERROR / 256.0 + 26 * u + S * ldexp(1, -22) : 0;
    const double lin_factor = lin > 0 ? 2 : 1;
    /* ... and the rounding of the frame's three axis steps, magnified (at most 12 roundings a
     * leaf: three steps over three levels, halved twice, and the centre's; the node's magnification
     * within twice the leaf's) */
#define LIN_STEPS(mag) (lin > 0 ? 24 * (mag) * u : 0)

    /* 2: each drawn point is the next matching leaf of the reference, within the bound */
    static unsigned char matched[MAX_PTS];
    memset(matched, 0, n_ref);
    size_t j = 0;
    for (size_t i = 0; i < n_fixed; i++) {
        while (j < n_ref && ref_pts[j].color != fixed_pts[i].color) j++;
        if (j == n_ref) {
            fail(&k->order_fail, "point %zu (colour at %p) is no leaf of the reference's walk in order: %s", i,
                 (const void *)fixed_pts[i].color, what);
            break;
        }
        const mc_ref_point *p = &ref_pts[j];
        matched[j++] = 1;
        double fx = fixed_pts[i].fx, fy = fixed_pts[i].fy;
        double bound = b_ortho, dist = 0;
        if (persp) {
            /* exact rotated position from the reference: depth = 1 - z (cube sides) */
            double z = 1 - p->depth;
            dist = eye - z;                               /* cube sides */
            if (!p->on_screen && dist < 1.0 / 64 + 1e-12) {
                /* the reference put it behind the near plane (its own rounding of dist decides a point
                 * exactly on the plane, and it then gives no projected position): only allowed within
                 * the depth error */
                if ((1.0 / 64 - dist) * S > b_ortho + u + qrel * S) {
                    fail(&k->pos_fail, "point %zu drawn %.3g cube sides behind the near plane: %s", i,
                         1.0 / 64 - dist, what);
                }
                k->near_plane_disagreements++;
                continue;
            }
            double mag = eye / dist;
            double ox = fabs(p->sx - cx), oy = fabs(p->sy - cy);
            double xx = ox / mag, yy = oy / mag;          /* |x|, |y| before the division, pixels */
            double dpx = dist * S - b_ortho - u;          /* dist in pixels, shrunk by its error */
            if (dpx <= 0) dpx = ldexp(1, -30);
            double bx = xx * qrel + xx * u / dpx + ox * (b_ortho + u) / dpx + mag * b_ortho + u;
            double by = yy * qrel + yy * u / dpx + oy * (b_ortho + u) / dpx + mag * b_ortho + u;
            bound = (bx > by ? bx : by) * lin_factor + lin + LIN_STEPS(mag);
        }
        double ex = fabs(fx - p->sx), ey = fabs(fy - p->sy), e = ex > ey ? ex : ey;
        k->points_checked++;
        if (e / bound > k->max_err_ratio) k->max_err_ratio = e / bound;
        if (persp) { if (e > k->max_err_px_persp) k->max_err_px_persp = e; }
        else if (e > k->max_err_px) k->max_err_px = e;
        if (ex > bound || ey > bound)
            fail(&k->pos_fail, "point %zu at (%.9f, %.9f), reference (%.9f, %.9f): error %.3g px over the bound %.3g: %s",
                 i, fx, fy, p->sx, p->sy, e, bound, what);
    }

    /* 3: every leaf clearly on screen is drawn (unless aborted), but for those the cones let go */
    static unsigned char back[MAX_PTS];
    const int culling = opt.cull != MC_CULL_OFF && back_facing_leaves(scene, &cv, d, back, n_ref);
    if (!st.aborted && j <= n_ref) {
        for (size_t r = 0; r < n_ref; r++) {
            const mc_ref_point *p = &ref_pts[r];
            if (!p->on_screen) continue;
            k->ref_on_screen++;
            if (matched[r]) continue;
            if (culling && back[r]) { k->culled_leaves++; continue; }
            double margin = b_ortho;
            if (persp) {
                double dist = eye - (1 - p->depth);
                if ((dist - 1.0 / 64) * S <= b_ortho + u + qrel * S) { k->near_plane_disagreements++; continue; }
                double mag = eye / dist;
                double dpx = dist * S - b_ortho - u;
                margin = ((fabs(p->sx - cx) + fabs(p->sy - cy)) * ((b_ortho + u) / dpx + qrel) + mag * b_ortho + 2 * u) *
                         lin_factor + lin + LIN_STEPS(mag);
            }
            if (p->sx < margin || p->sy < margin || p->sx >= w - margin || p->sy >= h - margin) continue;
            fail(&k->missing_fail, "leaf %zu on screen at (%.6f, %.6f) was not drawn: %s", r, p->sx, p->sy, what);
            break;
        }
    }

    /* 1 (finishing): every fill mode keeps to the target */
    for (size_t f = 0; f < sizeof fill_modes / sizeof fill_modes[0]; f++) {
        mc_finish(&t, fill_modes[f]);
        g = guards_check(n);
        if (g >= 0) fail(&k->guard_fail, "mc_finish mode %d changed guard element %ld: %s", (int)fill_modes[f], g, what);
    }
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s VIEWS [SEED]\n", argv[0]);
        return 2;
    }
    uint64_t views = strtoull(argv[1], NULL, 10);
    uint64_t seed = argc > 2 ? strtoull(argv[2], NULL, 10) : 1;
    rng_state = seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull;
    if (!rng_state) rng_state = 1;
    const mc_octree *scene = mc_app_model.model->octree;
    counters k;
    memset(&k, 0, sizeof k);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (uint64_t i = 0; i < views; i++) one_view(scene, &k);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double secs = (double)(t1.tv_sec - t0.tv_sec) + (t1.tv_nsec - t0.tv_nsec) / 1e9;

    const char *tag = argc > 3 ? argv[3] : "stress";
#define REPORT(cond, name, counter)                                                                            \
    do {                                                                                                       \
        if (cond) printf("ok - %s: %s (%" PRIu64 " views, seed %" PRIu64 ")\n", tag, name, k.views, seed);     \
        else printf("not ok - %s: %s: %" PRIu64 " failures; first: %s\n", tag, name, counter, first_failure);   \
    } while (0)
    REPORT(!k.guard_fail, "guard zones around colour and depth intact after mc_clear, mc_octree_render, mc_finish", k.guard_fail);
    REPORT(!k.order_fail, "every drawn point is a leaf of the reference walk, in stored order", k.order_fail);
    REPORT(!k.pos_fail, "every drawn point within the stated bound of its double-precision position", k.pos_fail);
    REPORT(!k.missing_fail, "every leaf clearly on screen is drawn, but back-facing ones (double-precision cone test)",
           k.missing_fail);
    REPORT(k.culled_leaves > 0, "the normal cones let back-facing leaves go", k.culled_leaves);
    REPORT(!k.stats_fail, "mc_stats.points equals the points plotted", k.stats_fail);
    REPORT(!k.rc_fail, "mc_octree_render returns MC_OK, and MC_ERR_SIZE for targets over MC_TARGET_MAX", k.rc_fail);
    REPORT(!k.lod_fail && k.lod_views > 0, "the level of detail (max_error) draws the level the double-precision rule picks",
           k.lod_fail);
#if STRESS_ALT
    REPORT(!k.alt_fail && k.alt_frames == k.views,
           STRESS_ALT_FORM " draws byte-identical colour and depth buffers", k.alt_fail);
#endif
    printf("# views %" PRIu64 " frames %" PRIu64 " (perspective %" PRIu64 ", aborted %" PRIu64 ", oversize refused %" PRIu64
           ") points %" PRIu64 " checked %" PRIu64 " reference on-screen %" PRIu64 " near-plane disagreements %" PRIu64
           " back-facing leaves skipped %" PRIu64 "\n",
           k.views, k.frames_drawn, k.persp, k.aborted, k.rejected, k.points, k.points_checked, k.ref_on_screen,
           k.near_plane_disagreements, k.culled_leaves);
#if MC_FLOAT
    /* the float bound depends on the coordinates' size: quote it for a 320x240 view, S = 240 */
    const double b240 = (scene->depth + 4) * (320 + 2 * 240) * ldexp(1, -24) + 240 * ldexp(1, -27);
#else
    const double b240 = (scene->depth + 1) * ldexp(1, -(MC_FRAC_BITS + 1)) + 240 * ldexp(1, -27);
#endif
    printf("# max error: orthographic %.3e px (bound at d=%u, S=240: %.3e px), perspective %.3e px; largest error/bound %.3f\n",
           k.max_err_px, (unsigned)scene->depth, b240, k.max_err_px_persp, k.max_err_ratio);
    printf("# seconds %.1f (%.1f us per view)\n", secs, secs * 1e6 / (double)(views ? views : 1));
    return (k.guard_fail | k.order_fail | k.pos_fail | k.missing_fail | k.stats_fail | k.rc_fail | k.alt_fail |
            k.lod_fail) ? 1 : 0;
}
