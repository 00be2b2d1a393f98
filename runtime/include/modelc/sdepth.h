/* The sparse depth buffer: depth (and optionally colour) entries at a few pixels of a frame, with
 * bit vectors that say which pixels hold one, so that a pass over faces visits only those pixels
 * (Kissling, Mitchell, Oskam and Gross's structure for edge-based tracking; modelc also draws its
 * hidden-line drawings with it, mesh_lines.h).
 *
 * Layout. Each row of width pixels is cut into blocks of 32 (MC_SDEPTH_BLOCKS(width) a row, the last
 * one partly outside the row). Per block one word of in-use bits: pixel x of the row is bit
 * 31 - (x mod 32) of word y * blocks + x / 32, so the count of leading zeros finds the leftmost pixel
 * in use. Per row, MC_SDEPTH_ROW_WORDS(width) words of block bits: block b's bit, 31 - (b mod 32) of
 * word y * row_words + b / 32, is set exactly when its in-use word is not 0, so that whole blocks
 * with nothing in them are skipped. The depths and colours are the caller's dense arrays (width *
 * height, row-major: a target's buffers, target.h), so an entry costs no more than a pixel of the
 * target; the bit vectors are 4 (blocks + row_words) bytes a row (1,024 bytes for 240 rows of 320).
 * A tracker keeps one more bit vector (mc_sdepth_keep_matched): per block, which of its entries
 * matched the camera's edge image when inserted (mc_sdepth_insert_matched), so that the visible and
 * the matched pixels of a pose are two population counts once the faces have removed the hidden ones.
 *
 * Promise: a pixel not in use holds empty_depth and empty_color (but after mc_sdepth_forget, which
 * leaves them stale for callers that go by the bits alone); a pixel in use holds the depth and
 * colour of the entry kept there. mc_sdepth_init makes every pixel empty (a full pass over the
 * arrays); mc_sdepth_clear empties the pixels in use only (work proportional to them and to the
 * blocks and rows, not to the area). mc_sdepth_insert keeps, of the entries given for a pixel, the
 * first one of the least depth (a later entry replaces the kept one only when strictly nearer).
 * Removal (mc_sdepth_remove, and the face pass of raster.h, mc_raster_triangle_hide) empties a pixel
 * and clears its bits. With matched bits kept, a pixel's matched bit is that of its kept entry (0 for
 * an entry inserted without one, and for a pixel not in use). No heap, no floating point, no
 * division. Freestanding.
 */
#ifndef MODELC_SDEPTH_H
#define MODELC_SDEPTH_H

#include <stdint.h>
#include "bits.h"
#include "target.h"

/* Blocks of 32 pixels in a row of w pixels, and words of block bits a row. */
#define MC_SDEPTH_BLOCKS(w) (((uint32_t)(w) + 31u) / 32u)
#define MC_SDEPTH_ROW_WORDS(w) ((MC_SDEPTH_BLOCKS(w) + 31u) / 32u)
/* Words of bit vectors for a w x h buffer: what mc_sdepth_init takes. */
#define MC_SDEPTH_WORDS(w, h) ((uint32_t)(h) * (MC_SDEPTH_BLOCKS(w) + MC_SDEPTH_ROW_WORDS(w)))
/* Words of matched bits for a w x h buffer: what mc_sdepth_keep_matched takes. */
#define MC_SDEPTH_MATCHED_WORDS(w, h) ((uint32_t)(h) * MC_SDEPTH_BLOCKS(w))

typedef struct mc_sdepth {
    uint16_t *depth;        /* width * height, the caller's */
    uint8_t *color;         /* width * height, the caller's, or null: no colours kept */
    uint32_t *used;         /* height * blocks in-use words */
    uint32_t *rows;         /* height * row_words block words */
    uint32_t *matched;      /* height * blocks matched words, or null: none kept */
    uint16_t width, height;
    uint16_t blocks, row_words;
    uint16_t empty_depth;   /* what a pixel not in use holds */
    uint8_t empty_color;
    uint16_t row_lo, row_hi; /* every row with an entry since the last clear lies in row_lo .. row_hi
                                (row_lo > row_hi: none), so that clearing passes over those rows only */
    uint32_t in_use;        /* pixels in use, kept as they change */
    uint32_t in_use_matched;   /* of those, matched (0 when no matched bits are kept) */
} mc_sdepth;

/* Sets s up for a width x height frame over the caller's arrays (bits: MC_SDEPTH_WORDS(width,
 * height) words; depth, and color unless null: width * height) and empties every pixel. Returns
 * MC_OK, MC_ERR_ARG (a null array other than color) or MC_ERR_SIZE (a side 0 or over
 * MC_TARGET_MAX). */
int mc_sdepth_init(mc_sdepth *s, uint16_t width, uint16_t height, uint32_t *bits, uint16_t *depth, uint8_t *color,
                   uint16_t empty_depth, uint8_t empty_color);

/* Keeps matched bits from now on in the caller's words (MC_SDEPTH_MATCHED_WORDS), every one 0 at
 * first (so the entries already in use count as unmatched); null stops keeping them. */
void mc_sdepth_keep_matched(mc_sdepth *s, uint32_t *matched);

/* Empties the pixels in use, and only those. */
void mc_sdepth_clear(mc_sdepth *s);

/* Empties the pixels in use as far as the bit vectors tell, leaving their depths and colours as they
 * were: a pixel not in use then holds empty_depth and empty_color only until an entry came and went.
 * For callers that read only pixels in use (the tracker: insertion, the face pass, the counts and
 * mc_sdepth_in_use all go by the bits), at the cost of a word per block with entries instead of a
 * write per pixel. */
void mc_sdepth_forget(mc_sdepth *s);

/* Pixels in use (kept as entries come and go: no work). */
static inline uint32_t mc_sdepth_count(const mc_sdepth *s) { return s->in_use; }

/* Pixels in use whose entry matched (0 when no matched bits are kept). */
static inline uint32_t mc_sdepth_count_matched(const mc_sdepth *s) { return s->in_use_matched; }

/* Whether any pixel of columns i0 .. i1 and rows j0 .. j1 (on the frame, i0 <= i1, j0 <= j1) is in
 * use. Inline: a face pass asks it of every face whose box holds a pixel centre. */
MC_ALWAYS_INLINE int mc_sdepth_any(const mc_sdepth *s, uint32_t i0, uint32_t i1, uint32_t j0, uint32_t j1)
{
    const uint32_t b0 = i0 >> 5, b1 = i1 >> 5;
    const uint32_t first = 0xFFFFFFFFu >> (i0 & 31u), last = 0xFFFFFFFFu << (31u - (i1 & 31u));
    const uint32_t *u = s->used + j0 * s->blocks;
    for (uint32_t j = j0; j <= j1; j++, u += s->blocks) {
        if (b0 == b1) {
            if (u[b0] & first & last) return 1;
            continue;
        }
        if ((u[b0] & first) || (u[b1] & last)) return 1;
        for (uint32_t b = b0 + 1; b < b1; b++)
            if (u[b]) return 1;
    }
    return 0;
}

/* Whether an entry of columns i0 .. i1 and rows j0 .. j1 (on the frame, i0 <= i1, j0 <= j1) lies at
 * depth z or farther. A face pass asks it before setting up a face or a group of faces: one whose
 * least depth is z hides only such entries. */
MC_ALWAYS_INLINE int mc_sdepth_any_from(const mc_sdepth *s, uint32_t i0, uint32_t i1, uint32_t j0, uint32_t j1, uint32_t z)
{
    const uint32_t b0 = i0 >> 5, b1 = i1 >> 5;
    const uint32_t first = 0xFFFFFFFFu >> (i0 & 31u), last = 0xFFFFFFFFu << (31u - (i1 & 31u));
    const uint32_t *u = s->used + j0 * s->blocks + b0;
    const uint16_t *d = s->depth + j0 * s->width + 32u * b0;
    for (uint32_t j = j0; j <= j1; j++, u += s->blocks, d += s->width) {
        uint32_t m = u[0] & first;
        for (uint32_t b = 0;;) {
            if (b == b1 - b0) m &= last;
            while (m) {
                const uint32_t c = mc_clz32(m);
                if (d[32u * b + c] >= z) return 1;
                m &= ~(0x80000000u >> c);
            }
            if (++b > b1 - b0) break;
            m = u[b];
        }
    }
    return 0;
}

/* Whether pixel (x, y) (on the frame) is in use. */
MC_ALWAYS_INLINE int mc_sdepth_in_use(const mc_sdepth *s, uint32_t x, uint32_t y)
{
    return (s->used[y * s->blocks + (x >> 5)] >> (31u - (x & 31u))) & 1u;
}

/* Whether pixel (x, y) (on the frame) holds an entry that matched (0 when no matched bits are kept). */
MC_ALWAYS_INLINE int mc_sdepth_is_matched(const mc_sdepth *s, uint32_t x, uint32_t y)
{
    return s->matched ? (s->matched[y * s->blocks + (x >> 5)] >> (31u - (x & 31u))) & 1u : 0;
}

/* mc_sdepth_insert, and with track (a constant where called) the entry's matched bit m as well. */
MC_ALWAYS_INLINE int mc_sdepth_put(mc_sdepth *s, uint32_t x, uint32_t y, uint16_t z, uint8_t c, uint32_t m, int track)
{
    const uint32_t i = y * s->width + x, w = y * s->blocks + (x >> 5), bit = 0x80000000u >> (x & 31u);
    const uint32_t u = s->used[w];
    if (u & bit) {
        if (z >= s->depth[i]) return 0;
        if (track) {   /* a nearer entry: its matched bit replaces the pixel's */
            const uint32_t was = s->matched[w] & bit;
            s->matched[w] = m ? s->matched[w] | bit : s->matched[w] & ~bit;
            s->in_use_matched += (uint32_t)(m != 0) - (uint32_t)(was != 0);
        }
    } else {
        s->used[w] = u | bit;
        if (!u) {   /* the block's first */
            s->rows[y * s->row_words + (x >> 10)] |= 0x80000000u >> ((x >> 5) & 31u);
            if (y < s->row_lo) s->row_lo = (uint16_t)y;
            if (y > s->row_hi) s->row_hi = (uint16_t)y;
        }
        s->in_use++;
        if (track) {   /* a pixel not in use has its matched bit 0; no branch on m, which a
                        * predictor cannot guess */
            s->matched[w] |= bit & (0u - (uint32_t)(m != 0));
            s->in_use_matched += (uint32_t)(m != 0);
        }
    }
    s->depth[i] = z;
    if (s->color) s->color[i] = c;
    return 1;
}

/* Offers pixel (x, y) (on the frame) an entry of depth z (below empty_depth to be told apart) and
 * colour c: stored when the pixel is empty or holds a farther entry (unmatched, where matched bits
 * are kept). Returns whether it was stored. */
MC_ALWAYS_INLINE int mc_sdepth_insert(mc_sdepth *s, uint32_t x, uint32_t y, uint16_t z, uint8_t c)
{
    return s->matched ? mc_sdepth_put(s, x, y, z, c, 0, 1) : mc_sdepth_put(s, x, y, z, c, 0, 0);
}

/* mc_sdepth_insert of an entry that matched the edge image (m not 0) or not (m 0), for a buffer that
 * keeps matched bits (s->matched not null): a stored entry's bit replaces the pixel's. */
MC_ALWAYS_INLINE int mc_sdepth_insert_matched(mc_sdepth *s, uint32_t x, uint32_t y, uint16_t z, uint8_t c, uint32_t m)
{
    return mc_sdepth_put(s, x, y, z, c, m, 1);
}

/* Empties pixel (x, y) (on the frame; in use or not). */
void mc_sdepth_remove(mc_sdepth *s, uint32_t x, uint32_t y);

#endif
