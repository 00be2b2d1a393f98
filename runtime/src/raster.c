/* Filled, flat-shaded triangles with a depth test: see modelc/raster.h.
 *
 * Cheap tests come first, in the order they reject on a dense mesh: the bounding box's pixel
 * centres on the target (exact in the 1/16 pixel coordinates: a centre on the box's right or bottom
 * side, or on its top side when that is not a horizontal edge, is never covered under the top-left
 * rule), then zero area and culling from the signed area. Only a triangle that can still cover a
 * pixel is set up.
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

/* n / d and n % d, d > 0, with 32-bit divisions only (the compilers' 64-bit division is a library
 * call on 32-bit targets): d below 2^32 by one or two divlu digits, else by Hacker's Delight's
 * divDU (a divlu by d's leading 32 bits, then one correction) */
static uint64_t udiv64(uint64_t n, uint64_t d, uint64_t *rem)
{
    const uint32_t nh = (uint32_t)(n >> 32), nl = (uint32_t)n;
    if ((d >> 32) == 0) {
        const uint32_t d32 = (uint32_t)d;
        uint32_t r;
        if (nh == 0) {
            *rem = nl % d32;
            return nl / d32;
        }
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
    uint32_t r;
    uint64_t q = ((uint64_t)divlu((uint32_t)(u1 >> 32), (uint32_t)u1, v1, &r) << s) >> 31;
    if (q != 0) q--;
    uint64_t left = n - q * d;   /* q is now the quotient or one less */
    if (left >= d) { q++; left -= d; }
    *rem = left;
    return q;
}

/* floor(n / d) and the remainder 0 <= rem < d, d > 0 */
static int64_t floor_div(int64_t n, uint64_t d, uint64_t *rem)
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

/* floor(v / 16) for |v| < 2^26, without shifting a negative number (implementation-defined in C99) */
static int32_t floor16(int32_t v)
{
    return (int32_t)((uint32_t)(v + ((int32_t)1 << 26)) >> 4) - ((int32_t)1 << 22);
}

/* the int64_t whose two's complement is u (a cast would be implementation-defined above INT64_MAX) */
static int64_t to_signed(uint64_t u)
{
    return u <= (uint64_t)INT64_MAX ? (int64_t)u : -(int64_t)~u - 1;
}

/* The triangle, oriented so that every edge function is positive inside, and its depth plane:
 * z(p) = z0 + (pa (px - x0) + pb (py - y0)) / area, |pa|, |pb| < 2^40. */
typedef struct tri {
    int32_t x[3], y[3];
    uint32_t z[3], zmin, zmax;
    uint64_t area;         /* twice the area, 1/256 pixel^2, below 2^46 */
    int64_t pa, pb;
} tri;

/* The plane at pixel (i, j) with FRAC fraction bits, plus 1/2 for rounding: its exact value rounded
 * to nearest, a value in [zmin, zmax] when the centre is in the triangle (|s| < 2^62 there). */
static uint64_t plane_at(const tri *g, int32_t i, int32_t j)
{
    const uint64_t s = (uint64_t)g->pa * (uint64_t)(int64_t)(16 * i + 8 - g->x[0]) +
                       (uint64_t)g->pb * (uint64_t)(int64_t)(16 * j + 8 - g->y[0]);
    uint64_t rz, rf;
    const int64_t qz = floor_div(to_signed(s), g->area, &rz);
    /* rz < area <= 2^46, so rz 2^FRAC fits */
    uint64_t frac = udiv64(rz << FRAC, g->area, &rf);
    frac += rf >= g->area - rf;
    return ((uint64_t)((int64_t)g->z[0] + qz) << FRAC) + frac + ((uint64_t)1 << (FRAC - 1));
}

/* the plane's step per pixel for coefficient p (pa across, pb down), FRAC fraction bits, rounded to
 * nearest (|16 p 2^FRAC| < 2^62), modulo 2^64 */
static uint64_t plane_step(const tri *g, int64_t p)
{
    return (uint64_t)round_div(p * ((int64_t)1 << (FRAC + MC_RASTER_SUBPIXEL_BITS)), g->area);
}

/* Writes pixels first .. last of a row whose first pixel has plane value acc (stepped by gx), with
 * the depth test. */
static void span(const tri *g, uint8_t *crow, uint16_t *drow, uint32_t first, uint32_t last, uint64_t acc,
                 uint64_t gx, uint8_t color)
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
 * the same sum the row path steps to; gx and gy are divided out only when a pixel needs them. */
static uint32_t draw_small(const mc_target *t, const tri *g, int32_t i0, int32_t i1, int32_t j0, int32_t j1,
                           uint8_t color)
{
    /* E_k(p) = dx (py - ay) - dy (px - ax) - bias, covered where all three are >= 0: bias 0 for a
     * left edge (dy < 0) or a top edge (dy = 0, dx > 0), whose centres are covered, else 1 */
    int32_t e[3], cx[3], cy[3];
    const int32_t px0 = 16 * i0 + 8, py0 = 16 * j0 + 8;
    for (int k = 0; k < 3; k++) {
        const int a = k, b = k == 2 ? 0 : k + 1;
        const int32_t dx = g->x[b] - g->x[a], dy = g->y[b] - g->y[a];
        const int32_t bias = dy > 0 || (dy == 0 && dx < 0);
        e[k] = dx * (py0 - g->y[a]) - dy * (px0 - g->x[a]) - bias;
        cx[k] = -16 * dy;
        cy[k] = 16 * dx;
    }
    const uint32_t width = t->width;
    uint8_t *crow = t->color + (uint32_t)j0 * width;
    uint16_t *drow = t->depth + (uint32_t)j0 * width;
    uint32_t count = 0;
    int32_t fi = 0, fj = -1;   /* fj < 0: no pixel covered yet */
    uint64_t base = 0, gx = 0, gy = 0;
    int have_gx = 0, have_gy = 0;
    for (int32_t j = j0; j <= j1; j++, crow += width, drow += width) {
        int32_t r0 = e[0], r1 = e[1], r2 = e[2], i = i0;
        e[0] += cy[0], e[1] += cy[1], e[2] += cy[2];
        while ((r0 | r1 | r2) < 0) {
            if (++i > i1) break;
            r0 += cx[0], r1 += cx[1], r2 += cx[2];
        }
        if (i > i1) continue;
        const int32_t lo = i;   /* the row's covered centres are one run (the triangle is convex) */
        do {
            ++i;
            r0 += cx[0], r1 += cx[1], r2 += cx[2];
        } while (i <= i1 && (r0 | r1 | r2) >= 0);
        const int32_t hi = i - 1;
        if (fj < 0) {
            base = plane_at(g, lo, j);
            fi = lo;
            fj = j;
        }
        uint64_t acc = base;
        if (j != fj) {
            if (!have_gy) gy = plane_step(g, g->pb), have_gy = 1;
            acc += (uint64_t)(int64_t)(j - fj) * gy;
        }
        if ((lo != fi || hi != lo) && !have_gx) gx = plane_step(g, g->pa), have_gx = 1;
        acc += (uint64_t)(int64_t)(lo - fi) * gx;
        span(g, crow, drow, (uint32_t)lo, (uint32_t)hi, acc, gx, color);
        count += (uint32_t)(hi - lo) + 1u;
    }
    return count;
}

/* The row path: spans from the edges' bounds, stepped from row to row. */
static uint32_t draw_rows(const mc_target *t, const tri *g, int32_t i0, int32_t i1, int32_t j0, int32_t j1,
                          uint8_t color)
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
            if (!have_plane) {
                gx = plane_step(g, g->pa);
                gy = plane_step(g, g->pb);
                row = plane_at(g, (int32_t)first, j) - first * gx;
                have_plane = 1;
            }
            span(g, crow, drow, first, last, row + first * gx, gx, color);
            count += last - first + 1u;
        }
        row += gy;
    }
    return count;
}

uint32_t mc_raster_triangle(const mc_target *t, const mc_raster_vertex v[3], uint8_t color, unsigned flags)
{
    tri g;
    for (int k = 0; k < 3; k++) {
        /* |x|, |y| <= MC_RASTER_COORD_LIMIT, one unsigned compare each */
        if ((uint32_t)v[k].x + (uint32_t)MC_RASTER_COORD_LIMIT > 2u * (uint32_t)MC_RASTER_COORD_LIMIT ||
            (uint32_t)v[k].y + (uint32_t)MC_RASTER_COORD_LIMIT > 2u * (uint32_t)MC_RASTER_COORD_LIMIT)
            return 0;
        g.x[k] = v[k].x;
        g.y[k] = v[k].y;
    }
    const int32_t *x = g.x, *y = g.y;
    /* The centres (16 i + 8, 16 j + 8) that can be covered lie in the bounding box, and not on its
     * right or bottom side: a centre there is on the rightmost (lowest) corner, whose incoming edge
     * (in the orientation below) is a right edge, or on a vertical right edge (a horizontal bottom
     * edge). Nor on its top side, unless that is a horizontal edge (two corners at ymin): else a
     * centre there is on the top corner, whose outgoing edge is a right edge. So columns have
     * xmin <= 16 i + 8 < xmax, rows ymin <= 16 j + 8 < ymax, and ymin < 16 j + 8 without a flat
     * top. */
    int32_t xmin = x[0], xmax = x[0], ymin = y[0], ymax = y[0];
    if (x[1] < xmin) xmin = x[1];
    if (x[1] > xmax) xmax = x[1];
    if (x[2] < xmin) xmin = x[2];
    if (x[2] > xmax) xmax = x[2];
    if (y[1] < ymin) ymin = y[1];
    if (y[1] > ymax) ymax = y[1];
    if (y[2] < ymin) ymin = y[2];
    if (y[2] > ymax) ymax = y[2];
    const int flat_top = (y[0] == ymin) + (y[1] == ymin) + (y[2] == ymin) == 2;
    int32_t j0 = floor16(ymin + 8 - flat_top), j1 = floor16(ymax - 9);
    int32_t i0 = floor16(xmin + 7), i1 = floor16(xmax - 9);
    const int32_t width = t->width, height = t->height;
    if (j0 < 0) j0 = 0;
    if (i0 < 0) i0 = 0;
    if (j1 > height - 1) j1 = height - 1;
    if (i1 > width - 1) i1 = width - 1;
    if (j0 > j1 || i0 > i1) return 0;   /* also an empty target */

    /* twice the signed area; below 2^46 in magnitude: a triangle fills at most half its 2^23-sided box */
    int64_t area = (int64_t)(x[1] - x[0]) * (y[2] - y[0]) - (int64_t)(x[2] - x[0]) * (y[1] - y[0]);
    if (area == 0) return 0;
    const int back = area > 0;
    if (back && (flags & MC_RASTER_CULL_BACK)) return 0;

    g.z[0] = v[0].z > ZMAX ? ZMAX : v[0].z;
    g.z[1] = v[1].z > ZMAX ? ZMAX : v[1].z;
    g.z[2] = v[2].z > ZMAX ? ZMAX : v[2].z;
    if (!back) {
        /* front face: swap two corners so that every edge function is positive inside */
        int32_t s = g.x[1]; g.x[1] = g.x[2]; g.x[2] = s;
        s = g.y[1]; g.y[1] = g.y[2]; g.y[2] = s;
        const uint32_t u = g.z[1]; g.z[1] = g.z[2]; g.z[2] = u;
        area = -area;
    }
    g.area = (uint64_t)area;
    g.zmin = g.zmax = g.z[0];
    for (int k = 1; k < 3; k++) {
        if (g.z[k] < g.zmin) g.zmin = g.z[k];
        if (g.z[k] > g.zmax) g.zmax = g.z[k];
    }
    const int64_t dx1 = x[1] - x[0], dy1 = y[1] - y[0], dx2 = x[2] - x[0], dy2 = y[2] - y[0];
    const int64_t dz1 = (int64_t)g.z[1] - g.z[0], dz2 = (int64_t)g.z[2] - g.z[0];
    g.pa = dz1 * dy2 - dz2 * dy1;
    g.pb = dx1 * dz2 - dx2 * dz1;

    if (xmax - xmin < SMALL_SIDE && ymax - ymin < SMALL_SIDE && (i1 - i0 + 1) * (j1 - j0 + 1) <= SMALL_CENTRES)
        return draw_small(t, &g, i0, i1, j0, j1, color);
    return draw_rows(t, &g, i0, i1, j0, j1, color);
}
