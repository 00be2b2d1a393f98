/* Image edges: see modelc/imgedge.h.
 *
 * One pass over the rows: row y's gradient gives its candidates (their code and thinning sector kept
 * in out, packed) and its magnitudes (a ring of three rows in scratch); row y - 1 is then thinned
 * against rows y - 2, y - 1 and y. */
#include "modelc/imgedge.h"
#include "modelc/bits.h"   /* MC_ALWAYS_INLINE */

/* tan of the orientation bins' boundaries (11.25, 33.75, 56.25, 78.75 degrees) and of the thinning
 * sectors' (22.5, 67.5 degrees), Q16, rounded to nearest */
#define TAN_11 UINT64_C(13036)
#define TAN_33 UINT64_C(43790)
#define TAN_56 UINT64_C(98082)
#define TAN_78 UINT64_C(329472)
#define TAN_22 UINT64_C(27146)
#define TAN_67 UINT64_C(158218)

/* The fold of (gx, gy) into angles (-90, 90] degrees (gx > 0, or gx = 0 and gy > 0): a = |gy| 2^16
 * and b = gx, the tangent's numerator and denominator, with the sign of gy */
MC_ALWAYS_INLINE void fold(int32_t gx, int32_t gy, uint64_t *a, uint64_t *b, int *neg)
{
    if (gx < 0 || (gx == 0 && gy < 0)) gx = -gx, gy = -gy;
    *a = (uint64_t)(gy < 0 ? 0u - (uint32_t)gy : (uint32_t)gy) << 16;
    *b = (uint32_t)gx;
    *neg = gy < 0;
}

/* The bin of a folded direction: how many boundaries |angle| passes, 0 (0 degrees) .. 4 (90 degrees),
 * taken the other way round the half circle for gy < 0 */
MC_ALWAYS_INLINE unsigned folded_bin(uint64_t a, uint64_t b, int neg)
{
    const unsigned k = (a > b * TAN_11) + (a > b * TAN_33) + (a > b * TAN_56) + (a > b * TAN_78);
    return neg ? (MC_IMGEDGE_DIRS - k) & (MC_IMGEDGE_DIRS - 1u) : k;
}

unsigned mc_imgedge_bin(int32_t gx, int32_t gy)
{
    uint64_t a, b;
    int neg;
    fold(gx, gy, &a, &b, &neg);
    return folded_bin(a, b, neg);
}

/* The packed work value of a candidate: code (1 + bin) in the low nibble, thinning sector in bits
 * 4-5: 0 (0 degrees), 1 (45), 2 (90), 3 (135: up-right and down-left) */
static uint8_t classify(int32_t gx, int32_t gy)
{
    uint64_t a, b;
    int neg;
    fold(gx, gy, &a, &b, &neg);
    const unsigned s = (a > b * TAN_22) + (a > b * TAN_67);
    const unsigned sector = neg ? (4u - s) & 3u : s;
    return (uint8_t)((1u + folded_bin(a, b, neg)) | sector << 4);
}

/* Thins row y (1 .. h-2) of out: its candidates' magnitudes mid against up (row y - 1) and down
 * (row y + 1). Returns the edge pixels kept. */
static uint32_t thin_row(uint8_t *o, const uint32_t *up, const uint32_t *mid, const uint32_t *down, uint16_t w)
{
    uint32_t kept = 0;
    for (uint32_t x = 1; x + 1 < w; x++) {
        const uint8_t c = o[x];
        if (!c) continue;
        const uint32_t m = mid[x];
        uint32_t behind, ahead;   /* against and along the gradient's direction, y down */
        switch (c >> 4) {
        case 0: behind = mid[x - 1], ahead = mid[x + 1]; break;    /* 0 degrees: +x */
        case 1: behind = up[x - 1], ahead = down[x + 1]; break;    /* 45: +x +y */
        case 2: behind = up[x], ahead = down[x]; break;            /* 90: +y */
        default: behind = up[x + 1], ahead = down[x - 1]; break;   /* 135: -x +y */
        }
        if (m > behind && m >= ahead) {
            o[x] = (uint8_t)(c & 15u);
            kept++;
        } else {
            o[x] = 0;
        }
    }
    return kept;
}

uint32_t mc_imgedge(const uint8_t *img, uint32_t stride, uint16_t w, uint16_t h, uint16_t threshold, uint8_t *out,
                    uint32_t *scratch)
{
    for (uint32_t i = 0; i < (uint32_t)w * h; i++) out[i] = 0;
    if (w < 3 || h < 3) return 0;
    if (threshold < 1) threshold = 1;
    if (threshold > MC_IMGEDGE_THRESHOLD_MAX) threshold = MC_IMGEDGE_THRESHOLD_MAX;
    const uint32_t t2 = (uint32_t)threshold * threshold;
    uint32_t *ring[3] = {scratch, scratch + w, scratch + 2u * w};
    for (uint32_t x = 0; x < w; x++) ring[0][x] = 0;   /* row 0: border, no gradient */
    uint32_t kept = 0;
    for (uint32_t y = 1; y + 1 < h; y++) {
        const uint8_t *a = img + (y - 1) * stride, *b = a + stride, *c = b + stride;
        uint32_t *m = ring[y % 3];
        uint8_t *o = out + y * w;
        m[0] = m[w - 1u] = 0;
        for (uint32_t x = 1; x + 1 < w; x++) {
            const int32_t gx = (int32_t)a[x + 1] + 2 * b[x + 1] + c[x + 1] - a[x - 1] - 2 * b[x - 1] - c[x - 1];
            const int32_t gy = (int32_t)c[x - 1] + 2 * c[x] + c[x + 1] - a[x - 1] - 2 * a[x] - a[x + 1];
            const uint32_t g = (uint32_t)(gx * gx + gy * gy);
            m[x] = g;
            if (g >= t2) o[x] = classify(gx, gy);
        }
        if (y >= 2) kept += thin_row(out + (y - 1) * w, ring[(y - 2) % 3], ring[(y - 1) % 3], m, w);
    }
    /* the last inner row against the border row below it (no gradient) */
    uint32_t *below = ring[(h - 1u) % 3];
    for (uint32_t x = 0; x < w; x++) below[x] = 0;
    kept += thin_row(out + (h - 2u) * w, ring[(h - 3u) % 3], ring[(h - 2u) % 3], below, w);
    return kept;
}

/* e |= src over n bytes (two rows of the frame, which never overlap) */
static void or_row(uint8_t *restrict e, const uint8_t *restrict src, uint32_t n)
{
    for (uint32_t x = 0; x < n; x++) e[x] |= src[x];
}

void mc_imgedge_masks(uint8_t *edges, uint16_t w, uint16_t h, unsigned radius, uint8_t *scratch)
{
    const uint32_t n = (uint32_t)w * h;
    for (uint32_t i = 0; i < n; i++) edges[i] = edges[i] ? (uint8_t)(1u << (edges[i] - 1u)) : 0;
    if (!radius || !n) return;
    /* across: each edge pixel of a row (a copy of it) ORed into x - radius .. x + radius; most
     * pixels are not edges, so the row costs about a read and a write a pixel */
    for (uint32_t y = 0; y < h; y++) {
        uint8_t *e = edges + y * w;
        for (uint32_t x = 0; x < w; x++) scratch[x] = e[x], e[x] = 0;
        for (uint32_t x = 0; x < w; x++) {
            const uint8_t m = scratch[x];
            if (!m) continue;
            const uint32_t a = x > radius ? x - radius : 0, b = x + radius < w ? x + radius : w - 1u;
            for (uint32_t k = a; k <= b; k++) e[k] |= m;
        }
    }
    /* down: row y from rows y - radius .. y + radius as they were: those above it kept in a ring of
     * radius + 1 rows of scratch before being overwritten, those below it not yet touched; whole
     * rows ORed in, one source row at a time */
    const uint32_t ring = radius + 1u;
    for (uint32_t y = 0; y < h; y++) {
        uint8_t *e = edges + y * w, *keep = scratch + (y % ring) * w;
        for (uint32_t x = 0; x < w; x++) keep[x] = e[x];
        const uint32_t top = y > radius ? y - radius : 0, bottom = y + radius < h ? y + radius : h - 1u;
        for (uint32_t k = top; k < y; k++) or_row(e, scratch + (k % ring) * w, w);
        for (uint32_t k = y + 1; k <= bottom; k++) or_row(e, edges + k * w, w);
    }
}
