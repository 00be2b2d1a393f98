/* Hole filling, the four-neighbour and the scanline criteria: see modelc/finish.h. */
#include "modelc/finish.h"

uint32_t mc_finish_pixel_holes(const mc_target *t)
{
    const int32_t w = t->width, h = t->height;
    uint16_t *zb = t->depth;
    uint8_t *fb = t->color;
    uint32_t filled = 0;
    for (int32_t y = 1; y + 1 < h; y++) {
        for (int32_t x = 1; x + 1 < w; x++) {
            const int32_t i = y * w + x;
            if (zb[i] != MC_DEPTH_EMPTY) continue;
            const uint16_t l = zb[i - 1], r = zb[i + 1], u = zb[i - w], d = zb[i + w];
            if (l == MC_DEPTH_EMPTY || r == MC_DEPTH_EMPTY || u == MC_DEPTH_EMPTY || d == MC_DEPTH_EMPTY) continue;
            /* the nearest neighbour; on ties the first of left, right, up, down */
            int32_t best = i - 1;
            uint16_t bz = l;
            if (r < bz) { best = i + 1; bz = r; }
            if (u < bz) { best = i - w; bz = u; }
            if (d < bz) { best = i + w; bz = d; }
            zb[i] = bz;
            fb[i] = fb[best];
            filled++;
        }
    }
    return filled;
}

/* ---- the scanline neighbourhood criterion (see modelc/finish.h) --------------------------------- */

#define K MC_FILL_REACH

/* The first drawn pixel from index i in steps of `step`, at most n steps; -1 if none. */
static inline int32_t ray(const uint16_t *zb, int32_t i, int32_t step, int32_t n)
{
    for (int32_t r = 0; r < n; r++) {
        i += step;
        if (zb[i] < MC_DEPTH_FILLED) return i;
    }
    return -1;
}

/* Whether the line through the empty pixel i in steps of `step` (at most n1 steps one way, n2 the
 * other) meets a drawn pixel on both sides; if so *best becomes the nearer (smaller depth) of them
 * and of what *best was. */
static inline int line(const uint16_t *zb, int32_t i, int32_t step, int32_t n1, int32_t n2, int32_t *best)
{
    int32_t a = ray(zb, i, -step, n1);
    if (a < 0) return 0;
    int32_t b = ray(zb, i, step, n2);
    if (b < 0) return 0;
    if (zb[b] < zb[a]) a = b;
    if (*best < 0 || zb[a] < zb[*best]) *best = a;
    return 1;
}

static inline int32_t min32(int32_t a, int32_t b) { return a < b ? a : b; }

/* One pass, row by row, each row's runs of empty pixels found once. Only the bounding box of the
 * drawn pixels is searched: outside it (and on its edge rows and columns) at least two of a pixel's
 * lines leave the box on one side, so none is filled there. A filled pixel gets the depth
 * MC_DEPTH_FILLED, so later rows do not take it for a drawn pixel. */
/* The first and last drawn pixel of a row; first = w, last = -1 when the row has none. */
static void row_extent(const uint16_t *row, int32_t w, int16_t ext[2])
{
    int32_t first = w, last = -1;
    for (int32_t x = 0; x < w; x++)
        if (row[x] < MC_DEPTH_FILLED) { first = x; break; }
    for (int32_t x = w - 1; x >= first; x--)
        if (row[x] < MC_DEPTH_FILLED) { last = x; break; }
    ext[0] = (int16_t)first;
    ext[1] = (int16_t)last;
}

uint32_t mc_finish_scanline_holes(const mc_target *t)
{
    const int32_t w = t->width, h = t->height;
    uint16_t *zb = t->depth;
    uint8_t *fb = t->color;
    int32_t bx0 = w, bx1 = -1, by0 = h, by1 = -1;   /* bounding box of the drawn pixels */
    for (int32_t y = 0; y < h; y++) {
        int16_t ext[2];
        row_extent(zb + y * w, w, ext);
        if (ext[1] < 0) continue;
        if (by0 == h) by0 = y;
        by1 = y;
        bx0 = ext[0] < bx0 ? ext[0] : bx0;
        bx1 = ext[1] > bx1 ? ext[1] : bx1;
    }
    /* The drawn extents of rows y-K..y+K, in a ring, taken before any of them is filled (fills
     * never count as drawn). A pixel whose row line is open needs its column bounded, so a drawn
     * pixel in its column above and one below: outside [vlo, vhi] it cannot be filled, and most of
     * the background inside the bounding box is rejected without reading its column. */
    int16_t ring[2 * K + 1][2];
    for (int32_t r = by0; r <= by1 && r <= by0 + 1 + K; r++) row_extent(zb + r * w, w, ring[r % (2 * K + 1)]);
    uint32_t filled = 0;
    for (int32_t y = by0 + 1; y < by1; y++) {
        const uint16_t *row = zb + y * w;
        const int32_t up = min32(K, y - by0), down = min32(K, by1 - y);
        if (y > by0 + 1 && y + K <= by1) row_extent(zb + (y + K) * w, w, ring[(y + K) % (2 * K + 1)]);
        int32_t ulo = w, uhi = -1, dlo = w, dhi = -1;
        for (int32_t r = 1; r <= up; r++) {
            const int16_t *e = ring[(y - r) % (2 * K + 1)];
            if (e[0] < ulo) ulo = e[0];
            if (e[1] > uhi) uhi = e[1];
        }
        for (int32_t r = 1; r <= down; r++) {
            const int16_t *e = ring[(y + r) % (2 * K + 1)];
            if (e[0] < dlo) dlo = e[0];
            if (e[1] > dhi) dhi = e[1];
        }
        const int32_t vlo = ulo > dlo ? ulo : dlo, vhi = uhi < dhi ? uhi : dhi;
        /* left of the row's first drawn pixel and right of its last the row line is open, so only
         * [vlo, vhi] can be filled there: scan [xs, xe) instead of the whole box width. A run cut
         * at xs or xe stays open on that side, as it is. */
        const int16_t *own = ring[y % (2 * K + 1)];
        const int32_t xs = own[0] < vlo ? own[0] : vlo, xe0 = own[1] + 1 > vhi + 1 ? own[1] + 1 : vhi + 1;
        const int32_t xe = xe0 < bx1 ? xe0 : bx1;
        int32_t x = xs > bx0 + 1 ? xs : bx0 + 1;
        while (x < xe) {
            if (row[x] < MC_DEPTH_FILLED) { x++; continue; }
            int32_t a = x, e = x;                          /* the run of holes [a, e) */
            while (e < xe && row[e] >= MC_DEPTH_FILLED) e++;
            for (; x < e; x++) {
                if (row[x] != MC_DEPTH_EMPTY) continue;
                const int32_t i = y * w + x, left = min32(K, x - bx0), right = min32(K, bx1 - x);
                int32_t best = -1;
                int open = 0;
                /* the row: bounded when the run is closed by drawn pixels within reach both sides */
                if (x - a < K && e - x <= K && row[a - 1] < MC_DEPTH_FILLED && row[e] < MC_DEPTH_FILLED) {
                    best = row[a - 1] <= row[e] ? i - (x - a + 1) : i + (e - x);
                } else {
                    if (x < vlo || x > vhi) continue;          /* row and column both open */
                    open = 1;
                }
                if (!line(zb, i, w, up, down, &best) && ++open > 1) continue;
                if (!line(zb, i, w + 1, min32(up, left), min32(down, right), &best) && ++open > 1) continue;
                if (!line(zb, i, w - 1, min32(up, right), min32(down, left), &best) && ++open > 1) continue;
                zb[i] = MC_DEPTH_FILLED;
                fb[i] = fb[best];
                filled++;
            }
        }
    }
    return filled;
}

uint32_t mc_finish(const mc_target *t, mc_fill mode)
{
    if (mode != MC_FILL_NONE && mode != MC_FILL_PIXEL && mode != MC_FILL_SCANLINE) mode = (mc_fill)MC_FILL_DEFAULT_MODE;
    switch (mode) {
    case MC_FILL_PIXEL: return mc_finish_pixel_holes(t);
    case MC_FILL_SCANLINE: return mc_finish_scanline_holes(t);
    default: return 0;
    }
}
