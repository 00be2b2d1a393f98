/* Filled, flat-shaded triangles with a depth test: see modelc/raster.h.
 *
 * Cheap tests come first, in the order they reject on a dense mesh: pixel centres in the bounding
 * box, on the target (exact in the 1/16 pixel coordinates, and as the top-left rule counts them: a
 * centre on the box's right or bottom side is never covered), then zero area and culling from the
 * signed area. Only a triangle that can still cover a pixel is set up.
 *
 * The triangle is put in one orientation (edge functions positive inside). A small one (a few
 * centres in its box, and a box small enough that its edge functions fit 32 bits) tests each centre
 * of its box with the three edge functions, stepped by additions. A larger one is drawn row by row:
 * each row's span is the intersection of the edges' half-planes at the row's centre line: a left
 * edge bounds the span from below, a right edge from above, a horizontal edge decides whole rows.
 * Each bound is a floor division that is solved once, at the first row, and then stepped exactly
 * from row to row by a quotient and a remainder.
 *
 * Depth is one plane in fixed point, set up at the first covered pixel (in row order): the value
 * there and the steps across and down, each the exact plane rounded to nearest. The small path
 * divides for a step only when a pixel needs it (a one-pixel triangle needs neither). The
 * divisions are 64-bit numbers by up to 64-bit divisors done with 32-bit divisions (udiv64):
 * Cortex-M3/M4 have those in hardware; there is no 64-bit division anywhere.
 */
#include "modelc/raster.h"
#include "modelc/bits.h"

#define FRAC MC_RASTER_DEPTH_FRAC_BITS
#define ZMAX (MC_DEPTH_EMPTY - 2u)

/* The small path: at most SMALL_CENTRES centres in the clipped box, and a box under SMALL_SIDE
 * (1/16 pixel) both ways, so that every edge function at a centre in it, |E| <= 2 SMALL_SIDE^2 =
 * 2^25, and its steps fit an int32_t. */
#define SMALL_CENTRES 24
#define SMALL_SIDE ((int32_t)1 << 12)

/* (u1 2^32 + u0) / v and the remainder, for u1 < v (so the quotient fits 32 bits), with two 32-bit
 * divisions by v's leading 16 bits and at most two corrections each: Hacker's Delight's divlu
 * (H. S. Warren, 2nd ed., figure 9-3) */
static uint32_t divlu(uint32_t u1, uint32_t u0, uint32_t v, uint32_t *rem)
{
    const uint32_t b = 65536u;
    const unsigned s = mc_clz32(v);   /* v > u1 >= 0: v is not 0 */
    v <<= s;
    const uint32_t vn1 = v >> 16, vn0 = v & 0xFFFFu;
    const uint32_t un32 = s ? u1 << s | u0 >> (32u - s) : u1;
    const uint32_t un10 = u0 << s, un1 = un10 >> 16, un0 = un10 & 0xFFFFu;
    uint32_t q1 = un32 / vn1, rhat = un32 - q1 * vn1;
    while (q1 >= b || q1 * vn0 > b * rhat + un1) {
        q1--;
        rhat += vn1;
        if (rhat >= b) break;
    }
    const uint32_t un21 = un32 * b + un1 - q1 * v;   /* modulo 2^32: the true value is below v */
    uint32_t q0 = un21 / vn1;
    rhat = un21 - q0 * vn1;
    while (q0 >= b || q0 * vn0 > b * rhat + un0) {
        q0--;
        rhat += vn1;
        if (rhat >= b) break;
    }
    *rem = (un21 * b + un0 - q0 * v) >> s;
    return q1 * b + q0;
}

/* n / d and n % d, d > 0, one of them at least 2^32, with 32-bit divisions only (the compilers'
 * 64-bit division is a library call on 32-bit targets): d below 2^32 by one or two divlu digits,
 * else by Hacker's Delight's divDU (a divlu by d's leading 32 bits, then one correction) */
static uint64_t udiv64_wide(uint64_t n, uint64_t d, uint64_t *rem)
{
    const uint32_t nh = (uint32_t)(n >> 32), nl = (uint32_t)n;
    uint32_t r;
    if ((d >> 32) == 0) {
        const uint32_t d32 = (uint32_t)d;
        if (nh < d32) {
            const uint32_t q = divlu(nh, nl, d32, &r);
            *rem = r;
            return q;
        }
        const uint32_t qh = nh / d32, ql = divlu(nh % d32, nl, d32, &r);
        *rem = r;
        return (uint64_t)qh << 32 | ql;
    }
    const unsigned s = mc_clz32((uint32_t)(d >> 32));   /* 0 .. 31 */
    const uint32_t v1 = (uint32_t)((d << s) >> 32);      /* d's leading 32 bits, top bit set */
    const uint64_t u1 = n >> 1;                          /* u1 / 2^32 < 2^31 <= v1 */
    uint64_t q = ((uint64_t)divlu((uint32_t)(u1 >> 32), (uint32_t)u1, v1, &r) << s) >> 31;
    if (q != 0) q--;
    uint64_t left = n - q * d;   /* q is now the quotient or one less */
    if (left >= d) { q++; left -= d; }
    *rem = left;
    return q;
}

/* n / d and n % d, d > 0: one 32-bit division when both fit 32 bits */
MC_ALWAYS_INLINE uint64_t udiv64(uint64_t n, uint64_t d, uint64_t *rem)
{
    if (((n | d) >> 32) == 0) {
        *rem = (uint32_t)n % (uint32_t)d;
        return (uint32_t)n / (uint32_t)d;
    }
    return udiv64_wide(n, d, rem);
}

/* floor(n / d) and the remainder 0 <= rem < d, d > 0 */
MC_ALWAYS_INLINE int64_t floor_div(int64_t n, uint64_t d, uint64_t *rem)
{
    uint64_t r, q;
    if (n >= 0) {
        q = udiv64((uint64_t)n, d, &r);
        *rem = r;
        return (int64_t)q;
    }
    q = udiv64((uint64_t)(-(n + 1)), d, &r);   /* -n - 1 = q d + r, so n = (-q - 1) d + (d - 1 - r) */
    *rem = d - 1u - r;
    return -(int64_t)q - 1;
}

/* n / d rounded to nearest, halves up, d > 0 */
static int64_t round_div(int64_t n, uint64_t d)
{
    uint64_t r;
    const int64_t q = floor_div(n, d, &r);
    return q + (r >= d - r);
}

#define floor16 mc_raster_floor16

/* the int64_t whose two's complement is u (a cast would be implementation-defined above INT64_MAX) */
MC_ALWAYS_INLINE int64_t to_signed(uint64_t u)
{
    return u <= (uint64_t)INT64_MAX ? (int64_t)u : -(int64_t)~u - 1;
}

/* The triangle: its corners in the orientation in which every edge function is positive inside,
 * and its depth plane, z(p) = z0 + (pa (px - x0) + pb (py - y0)) / area, |pa|, |pb| < 2^40, set up
 * at the first covered pixel (plane_first). The plane is the same in either orientation (swapping
 * two corners negates pa, pb and the signed area), so it is taken from the corners as given. */
typedef struct tri {
    const mc_raster_vertex *v;   /* the corners as given */
    int64_t sarea;               /* twice their signed area, 1/256 pixel^2, 0 < |sarea| < 2^46 */
    int32_t x[3], y[3];          /* oriented */
    uint32_t zmin, zmax;
    uint64_t area;               /* |sarea| */
    int64_t pa, pb;
    uint32_t offset;             /* the face pass's: the face hides an entry of depth e where e - offset >= its own */
} tri;

/* floor(m 2^k / d) and the remainder, for 0 < d < 2^31: long division by digits of as many bits as
 * d leaves free in 32 (at least one), each one 32-bit division; a small triangle (d below 2^14, a
 * few pixels) needs one digit for k up to 18 */
static uint64_t div_shl(uint32_t m, unsigned k, uint32_t d, uint32_t *rem)
{
    uint64_t q = m / d;
    uint32_t r = m % d;
    const unsigned b = mc_clz32(d);
    while (k) {
        const unsigned s = k < b ? k : b;
        r <<= s;   /* r < d < 2^(32 - b) */
        q = q << s | r / d;
        r %= d;
        k -= s;
    }
    *rem = r;
    return q;
}

/* n 2^k / d rounded to nearest, halves up (as round_div), for |n| < 2^32, 0 < d < 2^31, modulo 2^64 */
static uint64_t round_shl(int64_t n, unsigned k, uint32_t d)
{
    uint32_t r;
    const uint64_t q = div_shl((uint32_t)(n < 0 ? -n : n), k, d, &r);   /* |n| 2^k = q d + r */
    /* n >= 0: q, and 1 more when r / d >= 1/2; n < 0: -q, and 1 less when r / d > 1/2 */
    return n >= 0 ? q + ((uint64_t)r * 2u >= d) : 0u - q - ((uint64_t)r * 2u > d);
}

/* Sets up the plane and returns its value at pixel (i, j), a covered centre, with FRAC fraction
 * bits, plus 1/2 for rounding: the exact value rounded to nearest, in [zmin, zmax] (so |s| < 2^62:
 * s / area is z - z0 there, |z - z0| < 2^16). */
/* The corners' depths, clamped to ZMAX as the plane takes them, and their least and greatest in g:
 * the plane's value at a covered centre lies between those two. */
MC_ALWAYS_INLINE void depth_range(tri *g, uint32_t z[3])
{
    const mc_raster_vertex *v = g->v;
    for (int k = 0; k < 3; k++) z[k] = v[k].z > ZMAX ? ZMAX : v[k].z;
    const uint32_t zmin = z[0] < z[1] ? z[0] : z[1], zmax = z[0] > z[1] ? z[0] : z[1];
    g->zmin = z[2] < zmin ? z[2] : zmin;
    g->zmax = z[2] > zmax ? z[2] : zmax;
}

static uint64_t plane_first(tri *g, int32_t i, int32_t j)
{
    const mc_raster_vertex *v = g->v;
    uint32_t z[3];
    depth_range(g, z);
    const uint32_t z0 = z[0], z1 = z[1], z2 = z[2];
    const int64_t dx1 = v[1].x - v[0].x, dy1 = v[1].y - v[0].y, dx2 = v[2].x - v[0].x, dy2 = v[2].y - v[0].y;
    const int64_t dz1 = (int64_t)z1 - z0, dz2 = (int64_t)z2 - z0;
    int64_t pa = dz1 * dy2 - dz2 * dy1, pb = dx1 * dz2 - dx2 * dz1;
    uint64_t area = (uint64_t)g->sarea;
    if (g->sarea < 0) {
        pa = -pa, pb = -pb;
        area = 0u - area;
    }
    g->pa = pa, g->pb = pb, g->area = area;
    const uint64_t s = (uint64_t)pa * (uint64_t)(int64_t)(16 * i + 8 - v[0].x) +
                       (uint64_t)pb * (uint64_t)(int64_t)(16 * j + 8 - v[0].y);
    const uint64_t top = ((uint64_t)z0 << FRAC) + ((uint64_t)1 << (FRAC - 1));
    /* the value is z0 + s / area: its fraction rounded is round(s 2^FRAC / area) - z0 2^FRAC */
    if (area < ((uint64_t)1 << 16))   /* |s| < 2^16 area < 2^32 */
        return top + round_shl(to_signed(s), FRAC, (uint32_t)area);
    uint64_t rz, rf;
    const int64_t qz = floor_div(to_signed(s), area, &rz);
    /* rz < area <= 2^46, so rz 2^FRAC fits */
    uint64_t frac = udiv64(rz << FRAC, area, &rf);
    frac += rf >= area - rf;
    return top + ((uint64_t)qz << FRAC) + frac;
}

/* the plane's step per pixel for coefficient p (pa across, pb down), FRAC fraction bits, rounded to
 * nearest (|16 p 2^FRAC| < 2^62), modulo 2^64 */
static uint64_t plane_step(const tri *g, int64_t p)
{
    const unsigned k = FRAC + MC_RASTER_SUBPIXEL_BITS;
    if (g->area < ((uint64_t)1 << 31) && p < ((int64_t)1 << 32) && p > -((int64_t)1 << 32))
        return round_shl(p, k, (uint32_t)g->area);
    return (uint64_t)round_div(p * ((int64_t)1 << k), g->area);
}

/* The face pass over a sparse depth buffer (mc_raster_triangle_hide): of pixels first .. last of row
 * j, whose first pixel has plane value acc (stepped by gx), empties those in use whose entry is not
 * strictly nearer than the face there, visiting only the pixels in use (leading zeros of the in-use
 * words). Returns how many it emptied. */
MC_ALWAYS_INLINE uint32_t hide_span(const tri *g, mc_sdepth *s, uint32_t j, uint32_t first, uint32_t last,
                                    uint64_t acc, uint64_t gx)
{
    uint32_t *const u = s->used + j * s->blocks;
    const uint16_t *const drow = s->depth + j * s->width;
    const uint32_t zmin = g->zmin, zmax = g->zmax, b1 = last >> 5;
    uint32_t removed = 0;
    for (uint32_t b = first >> 5; b <= b1; b++) {
        uint32_t m = u[b];
        if (b == first >> 5) m &= 0xFFFFFFFFu >> (first & 31u);
        if (b == b1) m &= 0xFFFFFFFFu << (31u - (last & 31u));
        while (m) {
            const uint32_t c = mc_clz32(m), x = 32u * b + c;
            m &= ~(0x80000000u >> c);
            if (drow[x] < g->offset) continue;
            uint32_t d = (uint32_t)((acc + (uint64_t)(x - first) * gx) >> FRAC);
            if (d < zmin) d = zmin;
            if (d > zmax) d = zmax;
            if (d <= drow[x] - g->offset) {
                mc_sdepth_remove(s, x, j);
                removed++;
            }
        }
    }
    return removed;
}

/* Writes pixels first .. last of a row whose first pixel has plane value acc (stepped by gx), with
 * the depth test. */
MC_ALWAYS_INLINE void span(const tri *g, uint8_t *crow, uint16_t *drow, uint32_t first, uint32_t last,
                           uint64_t acc, uint64_t gx, uint8_t color)
{
    const uint32_t zmin = g->zmin, zmax = g->zmax;
    for (uint32_t i = first; i <= last; i++, acc += gx) {
        uint32_t d = (uint32_t)(acc >> FRAC);
        if (d < zmin) d = zmin;
        if (d > zmax) d = zmax;
        if (d < drow[i]) {
            drow[i] = (uint16_t)d;
            crow[i] = color;
        }
    }
}

/* The small path's plane over a sparse depth buffer, set up only when a pixel needs it: the anchor
 * is the triangle's first covered centre (fi, fj) in row order, as for a drawn triangle, so a value
 * is the same sum mc_raster_triangle forms there. */
typedef struct lazy_plane {
    int32_t fi, fj;              /* fj < 0: no centre covered yet */
    uint64_t base, gx, gy;
    uint8_t have_base, have_gx, have_gy;
} lazy_plane;

/* The plane's value (plus 1/2, FRAC fraction bits) at covered centre (x, j) */
static uint64_t lazy_value(tri *g, lazy_plane *p, int32_t x, int32_t j)
{
    if (!p->have_base) p->base = plane_first(g, p->fi, p->fj), p->have_base = 1;
    uint64_t acc = p->base;
    if (j != p->fj) {
        if (!p->have_gy) p->gy = plane_step(g, g->pb), p->have_gy = 1;
        acc += (uint64_t)(int64_t)(j - p->fj) * p->gy;
    }
    if (x != p->fi) {
        if (!p->have_gx) p->gx = plane_step(g, g->pa), p->have_gx = 1;
        acc += (uint64_t)(int64_t)(x - p->fi) * p->gx;
    }
    return acc;
}

/* The face pass's small path (mc_raster_triangle_hide) over covered centres lo .. hi of row j: as
 * hide_span, but a pixel's entry is compared with the corners' depth range first, and the plane is
 * set up only for an entry inside that range (an entry nearer than every corner stays, one not
 * nearer than any is emptied); pixels not in use cost one bit test. Returns how many it emptied. */
MC_ALWAYS_INLINE uint32_t hide_lazy(tri *g, mc_sdepth *s, lazy_plane *p, int32_t j, int32_t lo, int32_t hi)
{
    const uint16_t *const drow = s->depth + (uint32_t)j * s->width;
    uint32_t removed = 0;
    for (int32_t x = lo; x <= hi; x++) {
        if (!mc_sdepth_in_use(s, (uint32_t)x, (uint32_t)j)) continue;
        if (drow[x] < g->offset) continue;
        const uint32_t e = drow[x] - g->offset;
        if (g->zmin > e) continue;
        if (g->zmax > e) {
            uint32_t d = (uint32_t)(lazy_value(g, p, x, j) >> FRAC);
            if (d < g->zmin) d = g->zmin;
            if (d > g->zmax) d = g->zmax;
            if (d > e) continue;
        }
        mc_sdepth_remove(s, (uint32_t)x, (uint32_t)j);
        removed++;
    }
    return removed;
}

/* One edge's bound on the columns of the current row: bound = q exactly, q + r / d its fraction. */
typedef struct edge {
    int64_t q;
    uint32_t r, d;    /* 0 <= r < d = 16 |dy| <= 2^27 */
    int32_t sq;       /* per row: q += sq, r += sr, carrying into q */
    uint32_t sr;
    int left;         /* a lower bound (left edge), else an upper bound (right edge) */
} edge;

/* The small path: every centre of the box i0 .. i1, j0 .. j1 tested on its own. Depth: the value at
 * the first covered pixel (fi, fj), and at (i, j) that plus (i - fi) gx + (j - fj) gy modulo 2^64,
 * the same sum the row path steps to; gx and gy are divided out only when a pixel needs them (a
 * one-pixel triangle needs neither). */
MC_ALWAYS_INLINE uint32_t draw_small(const mc_target *t, mc_sdepth *sd, tri *g, int32_t i0, int32_t i1, int32_t j0,
                                     int32_t j1, uint8_t color)
{
    /* E_k(p) = dx (py - ay) - dy (px - ax) - bias for edge a -> b, covered where all three are
     * >= 0: bias 0 for a left edge (dy < 0) or a top edge (dy = 0, dx > 0), whose centres are
     * covered, else 1; that is, 0 where dy 2^13 - dx < 0 (|dx| < 2^12: the sign is dy's, or -dx's
     * for dy = 0; never both 0). */
    const int32_t x0 = g->x[0], y0 = g->y[0], x1 = g->x[1], y1 = g->y[1], x2 = g->x[2], y2 = g->y[2];
    const int32_t px = 16 * i0 + 8, py = 16 * j0 + 8;
    const int32_t dx0 = x1 - x0, dy0 = y1 - y0, dx1 = x2 - x1, dy1 = y2 - y1, dx2 = x0 - x2, dy2 = y0 - y2;
    int32_t e0 = dx0 * (py - y0) - dy0 * (px - x0) - (int32_t)(~(uint32_t)(dy0 * 8192 - dx0) >> 31);
    int32_t e1 = dx1 * (py - y1) - dy1 * (px - x1) - (int32_t)(~(uint32_t)(dy1 * 8192 - dx1) >> 31);
    int32_t e2 = dx2 * (py - y2) - dy2 * (px - x2) - (int32_t)(~(uint32_t)(dy2 * 8192 - dx2) >> 31);
    const uint32_t width = t->width;
    const uint32_t at = (uint32_t)j0 * width;
    lazy_plane lp;
    if (sd) {
        uint32_t z[3];
        depth_range(g, z);
        lp.fj = -1, lp.have_base = lp.have_gx = lp.have_gy = 0;
    }
    if (i0 == i1 && j0 == j1) {   /* one centre: most triangles of a dense mesh */
        if ((e0 | e1 | e2) < 0) return 0;
        if (sd) {
            lp.fi = i0, lp.fj = j0;
            return hide_lazy(g, sd, &lp, j0, i0, i0);
        }
        span(g, t->color + at, t->depth + at, (uint32_t)i0, (uint32_t)i0, plane_first(g, i0, j0), 0, color);
        return 1;
    }
    const int32_t cx0 = -16 * dy0, cx1 = -16 * dy1, cx2 = -16 * dy2;   /* per column */
    uint8_t *crow = t->color + at;
    uint16_t *drow = t->depth + at;
    uint32_t count = 0;
    int32_t fi = 0, fj = -1;   /* fj < 0: no pixel covered yet */
    uint64_t base = 0, gx = 0, gy = 0;
    int have_gx = 0, have_gy = 0;
    for (int32_t j = j0;;) {
        int32_t r0 = e0, r1 = e1, r2 = e2, i = i0;
        while ((r0 | r1 | r2) < 0 && i < i1) {
            i++;
            r0 += cx0, r1 += cx1, r2 += cx2;
        }
        if ((r0 | r1 | r2) >= 0) {
            const int32_t lo = i;   /* the row's covered centres are one run (the triangle is convex) */
            do {
                i++;
                r0 += cx0, r1 += cx1, r2 += cx2;
            } while (i <= i1 && (r0 | r1 | r2) >= 0);
            const int32_t hi = i - 1;
            if (sd) {
                if (lp.fj < 0) lp.fi = lo, lp.fj = j;
                count += hide_lazy(g, sd, &lp, j, lo, hi);
            } else {
                uint64_t acc;
                if (fj < 0) {
                    acc = base = plane_first(g, lo, j);
                    fi = lo;
                    fj = j;
                } else {
                    acc = base;
                    if (j != fj) {
                        if (!have_gy) gy = plane_step(g, g->pb), have_gy = 1;
                        acc += (uint64_t)(int64_t)(j - fj) * gy;
                    }
                }
                if ((lo != fi || hi != lo) && !have_gx) gx = plane_step(g, g->pa), have_gx = 1;
                acc += (uint64_t)(int64_t)(lo - fi) * gx;
                span(g, crow, drow, (uint32_t)lo, (uint32_t)hi, acc, gx, color);
                count += (uint32_t)(hi - lo) + 1u;
            }
        }
        if (++j > j1) break;
        e0 += 16 * dx0, e1 += 16 * dx1, e2 += 16 * dx2;
        crow += width, drow += width;
    }
    return count;
}

/* The row path: spans from the edges' bounds, stepped from row to row. Not inlined into the
 * triangle (draw_rows, draw_rows_hide below): the small path, most triangles of a dense mesh, keeps
 * its registers. */
MC_ALWAYS_INLINE uint32_t rows_path(const mc_target *t, mc_sdepth *sd, tri *g, int32_t i0, int32_t i1, int32_t j0,
                                    int32_t j1, uint8_t color)
{
    /* Edge a -> b, E(p) = dx (py - ay) - dy (px - ax), positive inside. At a centre px = 16 i + 8 on
     * row centre py, with ax - 8 = 16 k + m (0 <= m < 16):
     *   right edge (dy > 0), E >= 1:  i <= k + floor((dx (py - ay) + dy m - 1) / (16 dy))
     *   left edge (dy < 0), E >= 0:   i >= k + floor((-dx (py - ay) + |dy| m + 16 |dy| - 1) / (16 |dy|))
     * (a left edge is a top-left edge, so a centre on it is covered; a right edge is not). */
    edge e[3];
    int ne = 0;
    const int32_t py0 = 16 * j0 + 8;
    for (int k = 0; k < 3; k++) {
        const int a = k, b = k == 2 ? 0 : k + 1;
        const int32_t dx = g->x[b] - g->x[a], dy = g->y[b] - g->y[a];
        if (dy == 0) continue;   /* decided by the rows the box keeps */
        const int left = dy < 0;
        const int32_t sdx = left ? -dx : dx;
        const uint32_t ady = (uint32_t)(left ? -dy : dy);
        const uint32_t d = 16u * ady;
        const int32_t kk = floor16(g->x[a] - 8), m = g->x[a] - 8 - 16 * kk;
        const int64_t n = (int64_t)sdx * (py0 - g->y[a]) + (int64_t)ady * (uint32_t)m + (left ? (int64_t)d - 1 : -1);
        uint64_t r;
        e[ne].q = kk + floor_div(n, d, &r);
        e[ne].r = (uint32_t)r;
        e[ne].d = d;
        /* per row the numerator grows by 16 sdx, |16 dx| <= 2^27 */
        const int32_t step = 16 * sdx;
        int32_t sq = step / (int32_t)d, sr = step % (int32_t)d;
        if (sr < 0) { sr += (int32_t)d; sq--; }
        e[ne].sq = sq;
        e[ne].sr = (uint32_t)sr;
        e[ne].left = left;
        ne++;
    }

    /* Depth: gx, gy the steps per pixel across and down; row: the value, plus 1/2 for rounding,
     * extrapolated to column 0 of the current row. All three are kept modulo 2^64: extrapolated
     * values may overflow, but at a covered centre the sum is the true one (below
     * 2^(16 + FRAC + 1)), since only additions and multiplications lead to it. */
    uint64_t gx = 0, gy = 0, row = 0;
    int have_plane = 0;
    int32_t fi = 0, fj = -1;   /* the first covered centre (fj < 0: none yet) */

    uint32_t count = 0;
    const uint32_t width = t->width;
    uint8_t *crow = t->color + (uint32_t)j0 * width;
    uint16_t *drow = t->depth + (uint32_t)j0 * width;
    for (int32_t j = j0; j <= j1; j++, crow += width, drow += width) {
        int64_t lo = i0, hi = i1;
        for (int k = 0; k < ne; k++) {
            edge *h = &e[k];
            if (h->left) { if (h->q > lo) lo = h->q; }
            else if (h->q < hi) hi = h->q;
            h->q += h->sq;
            h->r += h->sr;
            if (h->r >= h->d) { h->r -= h->d; h->q++; }
        }
        if (lo <= hi) {
            const uint32_t first = (uint32_t)lo, last = (uint32_t)hi;
            if (fj < 0) fi = (int32_t)first, fj = j;   /* the plane's anchor, as a drawn triangle's */
            /* the face pass sets the plane up only for a row with a pixel in use under the span */
            if (!sd || mc_sdepth_any(sd, first, last, (uint32_t)j, (uint32_t)j)) {
                if (!have_plane) {
                    const uint64_t base = plane_first(g, fi, fj);
                    gx = plane_step(g, g->pa);
                    gy = plane_step(g, g->pb);
                    row = base - (uint64_t)(uint32_t)fi * gx + (uint64_t)(int64_t)(j - fj) * gy;
                    have_plane = 1;
                }
                if (sd) {
                    count += hide_span(g, sd, (uint32_t)j, first, last, row + first * gx, gx);
                } else {
                    span(g, crow, drow, first, last, row + first * gx, gx, color);
                    count += last - first + 1u;
                }
            }
        }
        row += gy;
    }
    return count;
}

MC_NOINLINE static uint32_t draw_rows(const mc_target *t, tri *g, int32_t i0, int32_t i1, int32_t j0, int32_t j1,
                                   uint8_t color)
{
    return rows_path(t, 0, g, i0, i1, j0, j1, color);
}
MC_NOINLINE static uint32_t draw_rows_hide(const mc_target *t, mc_sdepth *sd, tri *g, int32_t i0, int32_t i1, int32_t j0,
                                        int32_t j1)
{
    return rows_path(t, sd, g, i0, i1, j0, j1, 0);
}

/* The triangle either drawn into t (sd null) or hiding the entries of sd (t then describes sd's
 * frame), its box (mc_raster_centres, not empty) taken. A constant sd makes two functions of it. */
MC_ALWAYS_INLINE uint32_t triangle_in(const mc_target *t, mc_sdepth *sd, const mc_raster_vertex v[3], uint8_t color,
                                      unsigned flags, uint32_t offset, const mc_raster_box *box)
{
    /* (the row path relies on the box's rows: it leaves horizontal edges to them) */
    const int32_t i0 = box->i0, i1 = box->i1, j0 = box->j0, j1 = box->j1;
    const int32_t x0 = v[0].x, y0 = v[0].y, x1 = v[1].x, y1 = v[1].y, x2 = v[2].x, y2 = v[2].y;
    const int32_t xmin = mc_raster_min3(x0, x1, x2), xmax = mc_raster_max3(x0, x1, x2);
    const int32_t ymin = mc_raster_min3(y0, y1, y2), ymax = mc_raster_max3(y0, y1, y2);

    /* twice the signed area; below 2^46 in magnitude: a triangle fills at most half its 2^23-sided box */
    const int64_t area = (int64_t)(x1 - x0) * (y2 - y0) - (int64_t)(x2 - x0) * (y1 - y0);
    if (area == 0) return 0;
    tri g;
    g.v = v;
    g.sarea = area;
    g.offset = offset;
    g.x[0] = x0, g.y[0] = y0;
    if (area > 0) {   /* a back face: edge functions positive inside as given */
        if (flags & MC_RASTER_CULL_BACK) return 0;
        g.x[1] = x1, g.y[1] = y1, g.x[2] = x2, g.y[2] = y2;
    } else {          /* a front face: two corners swapped */
        g.x[1] = x2, g.y[1] = y2, g.x[2] = x1, g.y[2] = y1;
    }
    if (xmax - xmin < SMALL_SIDE && ymax - ymin < SMALL_SIDE && (i1 - i0 + 1) * (j1 - j0 + 1) <= SMALL_CENTRES)
        return draw_small(t, sd, &g, i0, i1, j0, j1, color);
    return sd ? draw_rows_hide(t, sd, &g, i0, i1, j0, j1) : draw_rows(t, &g, i0, i1, j0, j1, color);
}

uint32_t mc_raster_triangle(const mc_target *t, const mc_raster_vertex v[3], uint8_t color, unsigned flags)
{
    mc_raster_box box;
    if (!mc_raster_centres(v, t->width, t->height, &box)) return 0;
    return triangle_in(t, 0, v, color, flags, 0, &box);
}

uint32_t mc_raster_triangle_hide(mc_sdepth *s, const mc_raster_vertex v[3], unsigned flags)
{
    return mc_raster_triangle_hide_offset(s, v, flags, 0);
}

/* The face pass of a triangle whose box is taken (one copy for the callers below). */
static uint32_t hide_in(mc_sdepth *s, const mc_raster_vertex v[3], unsigned flags, uint32_t offset, const mc_raster_box *box)
{
    /* the plane's value at a covered centre is at least the least corner depth (depth_range), and an
     * entry goes only where that value, pushed back by offset, is no farther than the entry: a face
     * whose nearest corner so pushed lies beyond every entry of its box hides none, and is not set
     * up (most faces with an entry in their box, which lie beside the line, not before it) */
    const uint64_t least = (uint64_t)mc_raster_least_depth(v[0].z, v[1].z, v[2].z) + offset;
    if (least > 0xFFFFu ||
        !mc_sdepth_any_from(s, (uint32_t)box->i0, (uint32_t)box->i1, (uint32_t)box->j0, (uint32_t)box->j1, (uint32_t)least))
        return 0;
    mc_target t;
    /* the row pointers the drawing path steps are never read here; without colours they step
     * through the depth array's bytes, so that they always point into an array */
    t.color = s->color ? s->color : (uint8_t *)(void *)s->depth;
    t.depth = s->depth, t.width = s->width, t.height = s->height;
    return triangle_in(&t, s, v, 0, flags, offset, box);
}

uint32_t mc_raster_triangle_hide_offset(mc_sdepth *s, const mc_raster_vertex v[3], unsigned flags, uint32_t offset)
{
    mc_raster_box box;
    if (!mc_raster_centres(v, s->width, s->height, &box) ||
        !mc_sdepth_any(s, (uint32_t)box.i0, (uint32_t)box.i1, (uint32_t)box.j0, (uint32_t)box.j1))
        return 0;
    return hide_in(s, v, flags, offset, &box);
}

uint32_t mc_raster_triangle_hide_box(mc_sdepth *s, const mc_raster_vertex v[3], unsigned flags, const mc_raster_box *box)
{
    return hide_in(s, v, flags, 0, box);
}

uint64_t mc_raster_slope(const mc_raster_vertex v[3])
{
    const int64_t a = (int64_t)(v[1].x - v[0].x) * (v[2].y - v[0].y) - (int64_t)(v[2].x - v[0].x) * (v[1].y - v[0].y);
    if (a == 0) return 0;
    const int64_t z1 = (int64_t)v[1].z - v[0].z, z2 = (int64_t)v[2].z - v[0].z;
    /* dz/dx, dz/dy per 1/16 pixel: numerators below 2^16 2^23 each, |a| below 2^47 */
    const int64_t nx = z1 * (v[2].y - v[0].y) - z2 * (v[1].y - v[0].y);
    const int64_t ny = (int64_t)(v[1].x - v[0].x) * z2 - (int64_t)(v[2].x - v[0].x) * z1;
    const uint64_t gx = nx < 0 ? 0u - (uint64_t)nx : (uint64_t)nx, gy = ny < 0 ? 0u - (uint64_t)ny : (uint64_t)ny;
    const uint64_t g = gx > gy ? gx : gy, da = a < 0 ? 0u - (uint64_t)a : (uint64_t)a;
    uint64_t rem;
    return udiv64(g << MC_RASTER_SUBPIXEL_BITS, da, &rem) + 1u;
}
