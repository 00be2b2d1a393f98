/* The line walk shared by the line rasterizer (line.c) and the tracker's line pass (track.c): a
 * line's Bresenham steps on a w x h frame, clipped to it exactly (modelc/line.h states the rules).
 *
 * The walk works in (u, v): u the major axis, v the minor one, mirrored across the target when the
 * line runs towards v = 0 so that v only grows. Step i's minor offset is k(i) = ceil((2iM - D) / 2D),
 * kept as 2iM + D - 1 = 2D k + r with 0 <= r < 2D: r grows by 2M a step and k by one when r
 * reaches 2D (2M <= 2D, so never more). The depth is the same walk with 2|dz| for 2M.
 *
 * Private to runtime/src (static functions: each file that walks lines has its own copy, so a
 * program that draws no tracker links none of the tracker's walk).
 */
#ifndef MODELC_LINE_WALK_H
#define MODELC_LINE_WALK_H

#include "modelc/config.h"
#include "modelc/line.h"

/* MC_LINE_STEP_HOOK(): called once per iteration of every loop here; tests count with it that the
 * work follows the pixels on the target. Empty by default. */
#ifndef MC_LINE_STEP_HOOK
#define MC_LINE_STEP_HOOK() ((void)0)
#endif

/* n / d, and n % d into *rem, for n < d * 2^27 (every quotient here is at most 2^25 + 1): shift and
 * subtract, 27 steps, so no 64-bit division helper is needed (Cortex-M0 has no divide at all). Only
 * a clipped line's entry uses it. */
static uint32_t div27(uint64_t n, uint32_t d, uint32_t *rem)
{
    uint64_t dd = (uint64_t)d << 26;
    uint32_t q = 0;
    for (int b = 0; b < 27; b++) {
        MC_LINE_STEP_HOOK();
        q <<= 1;
        if (n >= dd) {
            n -= dd;
            q |= 1u;
        }
        dd >>= 1;
    }
    *rem = (uint32_t)n;
    return q;
}

/* The first step i whose minor offset k(i) reaches k, for 1 <= k <= m (so m >= 1): the smallest i
 * with 2im + d - 1 >= 2dk, ceil(((2k - 1) d + 1) / 2m), at most d. */
static uint32_t step_reaching(uint32_t k, uint32_t d, uint32_t m)
{
    uint32_t rem;
    return div27((uint64_t)(2u * k - 1u) * d + 2u * m, 2u * m, &rem);
}

static int coord_ok(int32_t c) { return c >= -MC_LINE_COORD_MAX && c <= MC_LINE_COORD_MAX; }

/* A line's walk over the run of its steps on a w x h frame: the first step's pixel (index idx, and
 * x, y), the steps, and the error terms of the minor coordinate (r against d2, growing by m2) and
 * of the depth (z, stepped by zstep and, when zr reaches d2, by zunit). */
typedef struct walk {
    uint32_t idx, count;
    uint32_t ustep, vstep;          /* index increments, modulo 2^32 */
    int32_t x, y, xu, yu, xv, yv;   /* the pixel, and its steps along u and v */
    uint32_t r, m2, d2;
    int32_t z, zstep, zunit;
    uint32_t zr, zrstep;
    uint32_t d, first;              /* the line's major steps D, and the first on the frame */
    int from_b;                     /* walked from b (the start: line.h) */
} walk;

/* Sets up the walk of the line from a to b on a w x h frame (w, h not 0); returns its step count on
 * the frame, 0 for none. */
MC_ALWAYS_INLINE uint32_t walk_init(uint32_t w, uint32_t h, mc_line_vertex a, mc_line_vertex b, walk *wk)
{
    if (!coord_ok(a.x) || !coord_ok(a.y) || !coord_ok(b.x) || !coord_ok(b.y) || !w || !h) return 0;
    uint32_t za = a.z < MC_LINE_DEPTH_MAX ? a.z : MC_LINE_DEPTH_MAX;
    uint32_t zb = b.z < MC_LINE_DEPTH_MAX ? b.z : MC_LINE_DEPTH_MAX;
    int32_t dx = b.x - a.x, dy = b.y - a.y;   /* |d| <= 2^25 */
    const uint32_t adx = dx < 0 ? 0u - (uint32_t)dx : (uint32_t)dx;
    const uint32_t ady = dy < 0 ? 0u - (uint32_t)dy : (uint32_t)dy;
    const int xmajor = adx >= ady;
    wk->from_b = xmajor ? dx < 0 : dy < 0;
    if (wk->from_b) {   /* walk from the start: the same line both ways */
        const mc_line_vertex tv = a;
        const uint32_t tz = za;
        a = b;
        b = tv;
        za = zb;
        zb = tz;
        dx = -dx;
        dy = -dy;
    } else if (!dx && !dy && zb < za) {
        za = zb;
    }

    int32_t u0, v0, vm0;
    uint32_t d, m, wu, wv, ustep, vstep;   /* steps: index increments, modulo 2^32 */
    int vneg;
    if (xmajor) {
        u0 = a.x, v0 = a.y, d = adx, m = ady, wu = w, wv = h, ustep = 1, vstep = w, vneg = dy < 0;
    } else {
        u0 = a.y, v0 = a.x, d = ady, m = adx, wu = h, wv = w, ustep = w, vstep = 1, vneg = dx < 0;
    }
    vm0 = vneg ? (int32_t)wv - 1 - v0 : v0;
    const int32_t u1 = u0 + (int32_t)d, vm1 = vm0 + (int32_t)m;
    const int32_t umax = (int32_t)wu - 1, vmax = (int32_t)wv - 1;

    /* Cohen-Sutherland: both endpoints beyond one side (u and vm grow from the start) */
    if (u1 < 0 || u0 > umax || vm1 < 0 || vm0 > vmax) return 0;
    /* the run of steps on the target: each side an endpoint's outcode names narrows it */
    uint32_t first = 0, last = d;
    if (u0 < 0) first = (uint32_t)-u0;
    if (u1 > umax) last = (uint32_t)(umax - u0);
    if (vm0 < 0) {
        const uint32_t i = step_reaching((uint32_t)-vm0, d, m);
        if (i > first) first = i;
    }
    if (vm1 > vmax) {
        const uint32_t i = step_reaching((uint32_t)(vmax - vm0) + 1u, d, m) - 1u;
        if (i < last) last = i;
    }
    if (first > last) return 0;   /* passes a corner */

    /* the error terms of step first (D = 0 is a single step: they are never used) */
    const uint32_t d2 = 2u * d, m2 = 2u * m;
    uint32_t k = 0, r = d ? d - 1u : 0;
    if (first) k = div27((uint64_t)first * m2 + (d - 1u), d2, &r);
    const uint32_t adz2 = 2u * (zb >= za ? zb - za : za - zb);
    const int32_t zunit = zb >= za ? 1 : -1;
    uint32_t zk = 0, zr = d ? d - 1u : 0, zq = 0, zrstep = 0;
    if (first) zk = div27((uint64_t)first * adz2 + (d - 1u), d2, &zr);
    if (d) {   /* 32-bit: a hardware divide or the compiler's helper */
        zq = adz2 / d2;
        zrstep = adz2 - zq * d2;
    }
    const int32_t zstep = zunit * (int32_t)zq;
    int32_t z = (int32_t)za + zunit * (int32_t)zk;

    const uint32_t ui = (uint32_t)u0 + first;   /* on the target: 0 .. wu-1 */
    const uint32_t vi = vneg ? (uint32_t)v0 - k : (uint32_t)v0 + k;
    wk->idx = xmajor ? vi * w + ui : ui * w + vi;
    wk->x = (int32_t)(xmajor ? ui : vi), wk->y = (int32_t)(xmajor ? vi : ui);
    wk->xu = xmajor, wk->yu = !xmajor;
    wk->xv = xmajor ? 0 : (vneg ? -1 : 1), wk->yv = xmajor ? (vneg ? -1 : 1) : 0;
    wk->ustep = ustep, wk->vstep = vneg ? 0u - vstep : vstep;
    wk->count = last - first + 1u;
    wk->d = d, wk->first = first;
    wk->r = r, wk->m2 = m2, wk->d2 = d2;
    wk->z = z, wk->zstep = zstep, wk->zunit = zunit, wk->zr = zr, wk->zrstep = zrstep;
    return wk->count;
}

/* One step along walk k from pixel (x, y), depth z and error terms r, zr. */
#if MC_LINE_SELECT
/* without branches (config.h): each step's "does the minor coordinate (the depth) move" as a mask
 * of all ones or zero */
#define MC_LINE_WALK_STEP(k, x, y, z, r, zr)                                              \
    do {                                                                                  \
        x += (uint32_t)(k).xu, y += (uint32_t)(k).yu;                                     \
        r += (k).m2;                                                                      \
        const uint32_t mv_ = 0u - (uint32_t)(r >= (k).d2);                                \
        r -= (k).d2 & mv_;                                                                \
        x += (uint32_t)(k).xv & mv_, y += (uint32_t)(k).yv & mv_;                         \
        z += (k).zstep;                                                                   \
        zr += (k).zrstep;                                                                 \
        const uint32_t mz_ = 0u - (uint32_t)(zr >= (k).d2);                               \
        zr -= (k).d2 & mz_;                                                               \
        z += (int32_t)((uint32_t)(k).zunit & mz_);                                        \
    } while (0)
#else
#define MC_LINE_WALK_STEP(k, x, y, z, r, zr)         \
    do {                                             \
        x += (uint32_t)(k).xu, y += (uint32_t)(k).yu; \
        r += (k).m2;                                 \
        if (r >= (k).d2) {                           \
            r -= (k).d2;                             \
            x += (uint32_t)(k).xv, y += (uint32_t)(k).yv; \
        }                                            \
        z += (k).zstep;                              \
        zr += (k).zrstep;                            \
        if (zr >= (k).d2) {                          \
            zr -= (k).d2;                            \
            z += (k).zunit;                          \
        }                                            \
    } while (0)
#endif

/* The walk's loop into a sparse depth buffer: each pixel at its depth less depth_offset (saturating
 * at 0), colour color, with its matched bit (masks & want) when track; masks and track are constants
 * where called, so each combination is its own loop. */
MC_ALWAYS_INLINE uint32_t walk_sdepth(mc_sdepth *s, walk *k, uint8_t color, uint16_t depth_offset, const uint8_t *masks,
                                      uint8_t want, int track)
{
    uint32_t r = k->r, zr = k->zr, x = (uint32_t)k->x, y = (uint32_t)k->y;
    int32_t z = k->z;
    for (uint32_t n = k->count;;) {
        MC_LINE_STEP_HOOK();
        const uint32_t zt = (uint32_t)z > depth_offset ? (uint32_t)z - depth_offset : 0;
        mc_sdepth_put(s, x, y, (uint16_t)zt, color, masks ? masks[y * s->width + x] & want : 0u, track);
        if (--n == 0) break;
        MC_LINE_WALK_STEP(*k, x, y, z, r, zr);
    }
    return k->count;
}

/* The pixels of line a b offered to a sparse depth buffer: line.h's mc_line_sdepth with masks null
 * (unmatched entries where the buffer keeps matched bits), the tracker's mc_track_line with masks
 * (each entry matched where masks has a bit of want set). Whether bits are kept is asked once a
 * line, not once a pixel. Returns the line's pixels on the frame. */
MC_ALWAYS_INLINE uint32_t mc_line_walk_sdepth(mc_sdepth *s, mc_line_vertex a, mc_line_vertex b, uint8_t color,
                                              uint16_t depth_offset, const uint8_t *masks, uint8_t want)
{
    walk k;
    if (!walk_init(s->width, s->height, a, b, &k)) return 0;
    if (masks) return walk_sdepth(s, &k, color, depth_offset, masks, want, 1);
    return s->matched ? walk_sdepth(s, &k, color, depth_offset, 0, 0, 1) : walk_sdepth(s, &k, color, depth_offset, 0, 0, 0);
}

#endif
