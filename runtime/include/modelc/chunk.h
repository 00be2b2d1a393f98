/* Chunked arrays: how the generator stores a long byte array, and a cursor that reads one in order.
 *
 * A chunked array is a list of mc_chunk {data, size} ending with a {0, 0} sentinel. The chunks may
 * live in different translation units (the generator's --chunk-bytes bounds each), so no compiler
 * and no class-file-like format limit is ever met. A part's descriptor points at such lists.
 *
 * Promise (mc_cursor): reads the chunks' bytes in order with one compare per read group: the caller
 * takes n bytes at a time (mc_cursor_take) where the writer guaranteed that a group of n bytes never
 * straddles two chunks, so the end of a chunk is tested once per group, not per byte. Empty chunks
 * are stepped over. mc_cursor_init_zeros gives a cursor over an endless run of zero bytes (a part
 * that stores no data for a stream, e.g. the colours of a monochrome octree): any group of at most
 * MC_CHUNK_ZERO_RUN bytes taken from it is zeros, and skipping over it moves nothing. Reading past
 * the sentinel of a real list is never done by a caller given a well-formed array; mc_cursor_skip
 * stops at the sentinel instead of running off.
 *
 * Promise (indexed records): a chunked array of fixed-size records in which every chunk but the
 * last holds exactly 2^shift records gives record i at one shift, one mask and one multiply
 * (mc_chunk_record), with no search. Multi-byte fields are little-endian and read a byte at a time
 * (mc_le16, mc_le32, mc_le_index), so records need no alignment and read the same everywhere.
 *
 * Header only (static inline): the renderers' hot loops inline the cursor and keep its fields in
 * registers, so the fields are part of the contract. Freestanding.
 */
#ifndef MODELC_CHUNK_H
#define MODELC_CHUNK_H

#include <stdint.h>
#include "bits.h"

typedef struct mc_chunk {
    const uint8_t *data;
    uint32_t size;
} mc_chunk;

/* A read position in a chunked byte array. */
typedef struct mc_cursor {
    const uint8_t *p, *end;   /* the rest of the current chunk */
    const mc_chunk *next;     /* the chunk after it */
} mc_cursor;

/* The zero run: a cursor over it is rewound whenever it reaches MC_CHUNK_ZERO_RUN bytes. Between two
 * tests of p >= end a caller takes at most one group (at most MC_CHUNK_ZERO_RUN bytes), so it never
 * reads past the run's second half. The cursor's end tests are >= rather than == only for this; real
 * chunks are never overrun, and the compare costs the same. */
#define MC_CHUNK_ZERO_RUN 64
static const uint8_t mc_chunk_zeros[2 * MC_CHUNK_ZERO_RUN] = {0};
static const mc_chunk mc_chunk_zero_run[2] = {{mc_chunk_zeros, MC_CHUNK_ZERO_RUN}, {0, 0}};
#define MC_CURSOR_IS_ZEROS(c) ((c)->next == mc_chunk_zero_run + 1)

static inline void mc_cursor_init(mc_cursor *c, const mc_chunk *chunks)
{
    c->p = chunks->data;
    c->end = chunks->data + chunks->size;
    c->next = chunks + 1;
}

static inline void mc_cursor_init_zeros(mc_cursor *c) { mc_cursor_init(c, mc_chunk_zero_run); }

/* Moves to the next non-empty chunk once the current one is used up. */
static inline void mc_cursor_refill(mc_cursor *c)
{
    if (MC_CURSOR_IS_ZEROS(c)) { c->p = mc_chunk_zeros; return; }
    while (c->p == c->end && c->next->data) {
        c->p = c->next->data;
        c->end = c->p + c->next->size;
        c->next++;
    }
}

/* The next n bytes, which the writer guarantees lie in one chunk. */
MC_ALWAYS_INLINE const uint8_t *mc_cursor_take(mc_cursor *c, uint32_t n)
{
    if (c->p >= c->end) mc_cursor_refill(c);
    const uint8_t *p = c->p;
    c->p += n;
    return p;
}

/* Steps over n bytes, across chunks. */
static inline void mc_cursor_skip(mc_cursor *c, uint32_t n)
{
    if (MC_CURSOR_IS_ZEROS(c)) return;   /* zeros: nothing to step over */
    while (n > (uint32_t)(c->end - c->p)) {
        n -= (uint32_t)(c->end - c->p);
        c->p = c->end;
        mc_cursor_refill(c);
        if (c->p == c->end) return;   /* the sentinel: only reachable with a corrupt array */
    }
    c->p += n;
}

/* Record i of an indexed array: chunks of 2^shift records of size bytes each. */
MC_ALWAYS_INLINE const uint8_t *mc_chunk_record(const mc_chunk *list, unsigned shift, uint32_t size, uint32_t i)
{
    return list[i >> shift].data + (i & ((UINT32_C(1) << shift) - 1u)) * size;
}

/* Little-endian fields. */
MC_ALWAYS_INLINE uint32_t mc_le16(const uint8_t *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8; }
MC_ALWAYS_INLINE uint32_t mc_le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
/* An index field of 2 or 4 bytes (a part's index width). */
MC_ALWAYS_INLINE uint32_t mc_le_index(const uint8_t *p, unsigned bytes) { return bytes == 2 ? mc_le16(p) : mc_le32(p); }

#endif
