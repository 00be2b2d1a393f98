/* Image edges: see modelc/imgedge.h.
 *
 * One pass over the rows: row y's gradient gives its candidates (their code and thinning sector kept
 * in out, packed) and its magnitudes (a ring of three rows in scratch); row y - 1 is then thinned
 * against rows y - 2, y - 1 and y. The Sobel sums are separable: gx = V(x+1) - V(x-1) with the
 * column sums V = a + 2 b + c of the three rows a, b, c, and gy = D(x-1) + 2 D(x) + D(x+1) with
 * D = c - a, so each pixel reads one new column. Most pixels of a frame are neither candidates nor
 * edges: the passes that look for them, and the masks' passes of ORs, go a word of bytes at a time
 * (bytes.h). */
#include "modelc/imgedge.h"
#include "modelc/bits.h"   /* MC_ALWAYS_INLINE */
#include "modelc/bytes.h"

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
static uint8_t candidate_code(int32_t gx, int32_t gy)
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
#if MC_WORDS
        /* a word of pixels with no candidate at once (the last pixel of the row is a border one) */
        while (x + MC_WORD_BYTES < w && !mc_words_load(o + x)) x += MC_WORD_BYTES;
        if (x + 1 >= w) break;
#endif
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

/* Pixel x's gradient (gx, gy): its squared magnitude into m, and its packed code into o when it is a
 * candidate (at least t2). */
MC_ALWAYS_INLINE void gradient(uint32_t *m, uint8_t *o, uint32_t x, int32_t gx, int32_t gy, uint32_t t2)
{
    const uint32_t g = (uint32_t)(gx * gx + gy * gy);
    m[x] = g;
    if (g >= t2) o[x] = candidate_code(gx, gy);
}

/* Column x's Sobel sums over the rows a, b, c: V = a + 2 b + c and D = c - a. */
#define COL_V(x) ((int32_t)a[x] + 2 * b[x] + c[x])
#define COL_D(x) ((int32_t)c[x] - a[x])

uint32_t mc_imgedge(const uint8_t *img, uint32_t stride, uint16_t w, uint16_t h, uint16_t threshold, uint8_t *out,
                    uint32_t *scratch)
{
    mc_bytes_zero(out, (uint32_t)w * h);
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
        /* the column sums of x - 1 and x, then each step brings in column x + 1 */
        int32_t v0 = COL_V(0), d0 = COL_D(0), v1 = COL_V(1), d1 = COL_D(1);
        uint32_t x = 1;
        for (; x + 2 < w; x += 2) {   /* two pixels a step: the sums roll without moves */
            const int32_t v2 = COL_V(x + 1), d2 = COL_D(x + 1), v3 = COL_V(x + 2), d3 = COL_D(x + 2);
            gradient(m, o, x, v2 - v0, d0 + 2 * d1 + d2, t2);
            gradient(m, o, x + 1, v3 - v1, d1 + 2 * d2 + d3, t2);
            v0 = v2, v1 = v3, d0 = d2, d1 = d3;
        }
        if (x + 1 < w) gradient(m, o, x, COL_V(x + 1) - v0, d0 + 2 * d1 + COL_D(x + 1), t2);   /* an odd run's last */
        if (y >= 2) kept += thin_row(out + (y - 1) * w, ring[(y - 2) % 3], ring[(y - 1) % 3], m, w);
    }
    /* the last inner row against the border row below it (no gradient) */
    uint32_t *below = ring[(h - 1u) % 3];
    for (uint32_t x = 0; x < w; x++) below[x] = 0;
    kept += thin_row(out + (h - 2u) * w, ring[(h - 3u) % 3], ring[(h - 2u) % 3], below, w);
    return kept;
}
#undef COL_V
#undef COL_D

/* The masks of a code (0: none, 1 + bin): bit bin. */
static const uint8_t code_mask[16] = {0, 1, 2, 4, 8, 16, 32, 64, 128, 0, 0, 0, 0, 0, 0, 0};

/* Row e (w bytes) spread across by radius < MC_WORD_BYTES, in place: each word ORed with itself
 * shifted by 1 .. radius bytes both ways and with the bytes of the words on either side that reach
 * into it (little-endian: byte k is pixel k), the row's ends counting as zeros. */
#if MC_WORDS
static void across_words(uint8_t *e, uint32_t w, unsigned radius)
{
    mc_word prev = 0, cur = w >= MC_WORD_BYTES ? mc_words_load(e) : mc_words_load_part(e, w);
    for (uint32_t i = 0; i < w; i += MC_WORD_BYTES) {
        const uint32_t j = i + MC_WORD_BYTES;   /* the next word's first byte */
        const mc_word next = j + MC_WORD_BYTES <= w ? mc_words_load(e + j) : j < w ? mc_words_load_part(e + j, w - j) : 0;
        mc_word r = cur;
        for (unsigned k = 1; k <= radius; k++)
            r |= cur << (8u * k) | cur >> (8u * k) | prev >> (8u * (MC_WORD_BYTES - k)) | next << (8u * (MC_WORD_BYTES - k));
        if (j <= w) {
            mc_words_store(e + i, r);
        } else {
            for (uint32_t k = 0; i + k < w; k++) e[i + k] = (uint8_t)(r >> (8u * k));
        }
        prev = cur, cur = next;
    }
}
#endif

/* Row e spread across by radius with one byte at a time (the row's copy in scratch) */
static void across_bytes(uint8_t *e, uint32_t w, unsigned radius, uint8_t *scratch)
{
    for (uint32_t x = 0; x < w; x++) scratch[x] = e[x], e[x] = 0;
    for (uint32_t x = 0; x < w; x++) {
        const uint8_t m = scratch[x];
        if (!m) continue;
        const uint32_t a = x > radius ? x - radius : 0, b = x + radius < w ? x + radius : w - 1u;
        for (uint32_t k = a; k <= b; k++) e[k] |= m;
    }
}

void mc_imgedge_masks(uint8_t *edges, uint16_t w, uint16_t h, unsigned radius, uint8_t *scratch)
{
    const uint32_t n = (uint32_t)w * h;
    /* codes to masks: most words hold no edge */
    uint32_t i = 0;
#if MC_WORDS
    for (; i + MC_WORD_BYTES <= n; i += MC_WORD_BYTES)
        if (mc_words_load(edges + i))
            for (uint32_t k = i; k < i + MC_WORD_BYTES; k++) edges[k] = code_mask[edges[k] & 15u];
#endif
    for (; i < n; i++) edges[i] = code_mask[edges[i] & 15u];
    mc_imgedge_spread(edges, w, h, radius, scratch);
}

void mc_imgedge_spread(uint8_t *edges, uint16_t w, uint16_t h, unsigned radius, uint8_t *scratch)
{
    if (!radius || !w || !h) return;
    /* across: each row on its own */
    for (uint32_t y = 0; y < h; y++) {
#if MC_WORDS
        if (radius < MC_WORD_BYTES) { across_words(edges + y * w, w, radius); continue; }
#endif
        across_bytes(edges + y * w, w, radius, scratch);
    }
    /* down: row y from rows y - radius .. y + radius as they were: those above it kept in a ring of
     * radius + 1 rows of scratch before being overwritten, those below it not yet touched; whole
     * rows ORed in, one source row at a time */
    const uint32_t ring = radius + 1u;
    for (uint32_t y = 0; y < h; y++) {
        uint8_t *e = edges + y * w, *keep = scratch + (y % ring) * w;
        mc_bytes_copy(keep, e, w);
        const uint32_t top = y > radius ? y - radius : 0, bottom = y + radius < h ? y + radius : h - 1u;
        for (uint32_t k = top; k < y; k++) mc_bytes_or(e, scratch + (k % ring) * w, w);
        for (uint32_t k = y + 1; k <= bottom; k++) mc_bytes_or(e, edges + k * w, w);
    }
}
