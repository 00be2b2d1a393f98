/* Filled, flat-shaded triangles with a depth test: see modelc/raster.h.
 *
 * The triangle is put in one orientation (edge functions positive inside), then each row's span is
 * the intersection of the edges' half-planes at the row's centre line: a left edge bounds the span
 * from below, a right edge from above, a horizontal edge decides whole rows. Each bound is a floor
 * division that is solved once, at the first row, and then stepped exactly from row to row by a
 * quotient and a remainder. Depth is one plane in fixed point, set up at the first covered pixel.
 */
#include "modelc/raster.h"
#include "modelc/bits.h"

#define FRAC MC_RASTER_DEPTH_FRAC_BITS
#define ZMAX (MC_DEPTH_EMPTY - 2u)

static unsigned clz64(uint64_t v)
{
    const uint32_t hi = (uint32_t)(v >> 32);
    return hi ? mc_clz32(hi) : 32u + mc_clz32((uint32_t)v);
}

/* n / d and n % d, d > 0, by shift and subtract over the quotient's bits only: the compilers' 64-bit
 * division is a library call on 32-bit targets, and a Cortex-M0 has no divide instruction at all */
static uint64_t udiv64(uint64_t n, uint64_t d, uint64_t *rem)
{
    uint64_t q = 0;
    if (((n | d) >> 32) == 0) {
        *rem = (uint32_t)n % (uint32_t)d;
        return (uint32_t)n / (uint32_t)d;
    }
    if (n >= d) {
        unsigned s = clz64(d) - clz64(n);
        d <<= s;
        for (;;) {   /* branch-free step: which way it goes is a coin toss to a predictor */
            const uint64_t take = 0u - (uint64_t)(n >= d);
            n -= d & take;
            q = q << 1 | (take & 1u);
            if (s-- == 0) break;
            d >>= 1;
        }
    }
    *rem = n;
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

/* floor(v / 16) without shifting a negative number (implementation-defined in C99) */
static int32_t floor16(int32_t v)
{
    return v >= 0 ? v / 16 : -((15 - v) / 16);
}

/* the int64_t whose two's complement is u (a cast would be implementation-defined above INT64_MAX) */
static int64_t to_signed(uint64_t u)
{
    return u <= (uint64_t)INT64_MAX ? (int64_t)u : -(int64_t)~u - 1;
}

/* One edge's bound on the columns of the current row: bound = q exactly, q + r / d its fraction. */
typedef struct edge {
    int64_t q;
    uint32_t r, d;    /* 0 <= r < d = 16 |dy| <= 2^27 */
    int32_t sq;       /* per row: q += sq, r += sr, carrying into q */
    uint32_t sr;
    int left;         /* a lower bound (left edge), else an upper bound (right edge) */
} edge;

uint32_t mc_raster_triangle(const mc_target *t, const mc_raster_vertex v[3], uint8_t color, unsigned flags)
{
    int32_t x[3], y[3];
    uint32_t z[3];
    for (int k = 0; k < 3; k++) {
        if (v[k].x < -MC_RASTER_COORD_LIMIT || v[k].x > MC_RASTER_COORD_LIMIT ||
            v[k].y < -MC_RASTER_COORD_LIMIT || v[k].y > MC_RASTER_COORD_LIMIT)
            return 0;
        x[k] = v[k].x;
        y[k] = v[k].y;
        z[k] = v[k].z > ZMAX ? ZMAX : v[k].z;
    }
    /* twice the signed area; below 2^46 in magnitude: a triangle fills at most half its 2^23-sided box */
    int64_t area = (int64_t)(x[1] - x[0]) * (y[2] - y[0]) - (int64_t)(x[2] - x[0]) * (y[1] - y[0]);
    if (area == 0) return 0;
    if (area > 0) {
        if (flags & MC_RASTER_CULL_BACK) return 0;
    } else {
        /* front face: swap two corners so that every edge function is positive inside */
        int32_t s = x[1]; x[1] = x[2]; x[2] = s;
        s = y[1]; y[1] = y[2]; y[2] = s;
        const uint32_t u = z[1]; z[1] = z[2]; z[2] = u;
        area = -area;
    }
    const uint32_t width = t->width, height = t->height;
    if (width == 0 || height == 0) return 0;

    int32_t xmin = x[0], xmax = x[0], ymin = y[0], ymax = y[0];
    uint32_t zmin = z[0], zmax = z[0];
    for (int k = 1; k < 3; k++) {
        if (x[k] < xmin) xmin = x[k];
        if (x[k] > xmax) xmax = x[k];
        if (y[k] < ymin) ymin = y[k];
        if (y[k] > ymax) ymax = y[k];
        if (z[k] < zmin) zmin = z[k];
        if (z[k] > zmax) zmax = z[k];
    }
    /* rows and columns whose centres (16 i + 8) lie in the bounding box, on the target; a horizontal
     * bottom edge (two corners at ymax) is not a top edge, so its row of centres is left out */
    const int flat_bottom = (y[0] == ymax) + (y[1] == ymax) + (y[2] == ymax) == 2;
    int32_t j0 = floor16(ymin + 7), j1 = floor16(ymax - 8 - flat_bottom);
    int32_t i0 = floor16(xmin + 7), i1 = floor16(xmax - 8);
    if (j0 < 0) j0 = 0;
    if (i0 < 0) i0 = 0;
    if (j1 > (int32_t)height - 1) j1 = (int32_t)height - 1;
    if (i1 > (int32_t)width - 1) i1 = (int32_t)width - 1;
    if (j0 > j1 || i0 > i1) return 0;

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
        const int32_t dx = x[b] - x[a], dy = y[b] - y[a];
        if (dy == 0) continue;   /* decided by the rows above */
        const int left = dy < 0;
        const int32_t sdx = left ? -dx : dx;
        const uint32_t ady = (uint32_t)(left ? -dy : dy);
        const uint32_t d = 16u * ady;
        const int32_t kk = floor16(x[a] - 8), m = x[a] - 8 - 16 * kk;
        const int64_t n = (int64_t)sdx * (py0 - y[a]) + (int64_t)ady * (uint32_t)m + (left ? (int64_t)d - 1 : -1);
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

    /* Depth: z(p) = z0 + (A (px - x0) + B (py - y0)) / area, |A|, |B| < 2^40. gx, gy: its steps per
     * pixel across and down, with FRAC fraction bits (|16 A 2^FRAC| < 2^62); row: the value, plus 1/2
     * for rounding, extrapolated to column 0 of the current row. All three are kept modulo 2^64:
     * extrapolated values may overflow, but at a covered centre the sum is the true one (below
     * 2^(16 + FRAC + 1)), since only additions and multiplications lead to it. */
    const int64_t dx1 = x[1] - x[0], dy1 = y[1] - y[0], dx2 = x[2] - x[0], dy2 = y[2] - y[0];
    const int64_t dz1 = (int64_t)z[1] - z[0], dz2 = (int64_t)z[2] - z[0];
    const int64_t pa = dz1 * dy2 - dz2 * dy1, pb = dx1 * dz2 - dx2 * dz1;
    uint64_t gx = 0, gy = 0, row = 0;
    int have_plane = 0;

    uint32_t count = 0;
    uint8_t *crow = t->color + (uint32_t)j0 * width;
    uint16_t *drow = t->depth + (uint32_t)j0 * width;
    for (int32_t j = j0; j <= j1; j++, crow += width, drow += width) {
        int64_t lo = i0, hi = i1;
        for (int k = 0; k < ne; k++) {
            edge *g = &e[k];
            if (g->left) { if (g->q > lo) lo = g->q; }
            else if (g->q < hi) hi = g->q;
            g->q += g->sq;
            g->r += g->sr;
            if (g->r >= g->d) { g->r -= g->d; g->q++; }
        }
        if (lo <= hi) {
            const uint32_t first = (uint32_t)lo, last = (uint32_t)hi;
            if (!have_plane) {
                /* the exact plane at this covered centre, a value in [zmin, zmax]; |S| < 2^62 */
                const uint64_t s = (uint64_t)pa * (uint64_t)(int64_t)(16 * (int32_t)first + 8 - x[0]) +
                                   (uint64_t)pb * (uint64_t)(int64_t)(16 * j + 8 - y[0]);
                uint64_t rz, rf;
                const int64_t qz = floor_div(to_signed(s), (uint64_t)area, &rz);
                /* rz < area <= 2^46, so rz 2^FRAC fits */
                uint64_t frac = udiv64(rz << FRAC, (uint64_t)area, &rf);
                frac += rf >= (uint64_t)area - rf;
                gx = (uint64_t)round_div(pa * ((int64_t)1 << (FRAC + MC_RASTER_SUBPIXEL_BITS)), (uint64_t)area);
                gy = (uint64_t)round_div(pb * ((int64_t)1 << (FRAC + MC_RASTER_SUBPIXEL_BITS)), (uint64_t)area);
                row = ((uint64_t)((int64_t)z[0] + qz) << FRAC) + frac + ((uint64_t)1 << (FRAC - 1)) - first * gx;
                have_plane = 1;
            }
            uint64_t acc = row + first * gx;
            for (uint32_t i = first; i <= last; i++, acc += gx) {
                uint32_t d = (uint32_t)(acc >> FRAC);
                if (d < zmin) d = zmin;
                if (d > zmax) d = zmax;
                if (d < drow[i]) {
                    drow[i] = (uint16_t)d;
                    crow[i] = color;
                }
            }
            count += last - first + 1u;
        }
        row += gy;
    }
    return count;
}
