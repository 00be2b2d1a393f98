/* Streamed octrees: a bake as one binary stream, coarse levels first, and its reader.
 *
 * Promise: mc_stream_feed takes a stream in pieces of any size (bytes as they arrive from a file, a
 * pipe, a socket, a fetch or a UART) into the caller's buffer, checks every complete record as it
 * lands, and mc_stream_octree then describes the deepest level d whose records 0..d are all complete
 * and checked: an mc_octree of depth d that the point renderer draws exactly as it draws the baked
 * octree at depth d (the same masks, colours, palette and cones, so the same pixels). Everything the
 * renderer relies on is checked before a level counts, with a CRC-32 on each record besides: node
 * counts against the masks above, no empty mask, colour indices within the palette, each cone's
 * subtree counts against the masks below it (they come with the level three below theirs). A stream that turns out truncated, corrupted, of
 * another version or larger than the buffer stops the reader with an error (sticky, with the byte
 * offset where it was found); what was drawable before stays drawable, so a front end keeps its last
 * good frame. No heap: the caller owns the buffer (sized at bake time: budget.json "stream") and
 * the mc_stream. Freestanding; work proportional to the bytes fed.
 *
 * The format, version 1 (all integers little-endian):
 *   header, 20 bytes:  "mcs" 0x1A | u16 version (1) | u8 depth D (1..MC_MAX_DEPTH) | u8 flags (0) |
 *                      u16 palette entries P (1..256) | u16 0 | u32 total bytes of the stream |
 *                      u32 CRC-32 of the 16 bytes before it
 *   then records:      u8 kind | u8 level | u16 0 | u32 payload bytes n | n bytes | u32 CRC-32 of the
 *                      8 + n bytes before it
 *     kind 1, palette: P RGB triplets; first, and once
 *     kind 2, level l: levels 0, 1, ..., D in order: u32 nodes N | N child masks (l < D) |
 *                      N palette indices (l >= 1 and P > 1) | the 7-byte normal cones of level l-3's
 *                      nodes (octree.h), the first depth that culls with them, for l-3 >= 1 where the
 *                      bake has cones (told apart by n)
 *     kind 3, end:     no payload; last, and the stream's total is where it ends
 * A prefix that holds the header, the palette and the levels 0..d is a drawable model of depth d:
 * each level costs about four times the one above it, so the first picture comes after a small
 * part of the bytes. The generator writes it with --emit stream (gen/emit_stream.cpp).
 */
#ifndef MODELC_STREAM_H
#define MODELC_STREAM_H

#include <stdint.h>
#include "config.h"
#include "octree.h"

#define MC_STREAM_VERSION 1
#define MC_STREAM_HEADER_BYTES 20
#define MC_STREAM_RECORD_BYTES 12   /* a record's own bytes around its payload */

enum {
    MC_STREAM_OK = 0,
    MC_STREAM_ERR_MAGIC = -1,      /* not a modelc stream */
    MC_STREAM_ERR_VERSION = -2,    /* a version this reader does not know */
    MC_STREAM_ERR_HEADER = -3,     /* a header field out of range */
    MC_STREAM_ERR_SIZE = -4,       /* larger than the buffer */
    MC_STREAM_ERR_CRC = -5,        /* a header or record whose CRC-32 does not match */
    MC_STREAM_ERR_RECORD = -6,     /* a record of the wrong kind, order or length */
    MC_STREAM_ERR_NODES = -7,      /* a level's node count not what the masks above it say */
    MC_STREAM_ERR_VALUE = -8,      /* an empty mask or a colour outside the palette */
    MC_STREAM_ERR_CONE = -9,       /* a cone's subtree counts not what the masks below it say */
    MC_STREAM_ERR_TRAILING = -10,  /* bytes after the end record */
    MC_STREAM_ERR_TRUNCATED = -11, /* the input ended before the end record (mc_stream_end) */
    MC_STREAM_ERR_ARG = -12        /* a NULL pointer */
};

typedef struct mc_stream {
    uint8_t *buf;                  /* the caller's buffer: the stream's bytes as they came */
    uint32_t cap, len;             /* its size, the bytes in it */
    uint32_t at;                   /* the first byte not yet checked */
    uint32_t total;                /* the header's total (0 until the header is read) */
    int error;                     /* MC_STREAM_OK or the first error (sticky) */
    uint32_t error_at;             /* the byte offset where it was found */
    int ended;                     /* the end record was read */
    unsigned levels_read;          /* complete, checked levels: 0..levels_read-1 */
    uint8_t depth;                 /* D of the header */
    uint16_t palette_size;
    /* where each level's arrays lie in buf (offsets, 0 = none), and its node count */
    uint32_t nodes[MC_MAX_DEPTH + 1];
    uint32_t masks_at[MC_MAX_DEPTH + 1], colors_at[MC_MAX_DEPTH + 1], cones_at[MC_MAX_DEPTH + 1];
    uint32_t palette_at;
    /* the descriptor of the drawable prefix, rebuilt whenever a level completes */
    mc_octree octree;
    mc_octree_level level[MC_MAX_DEPTH + 1];
    mc_chunk chunks[MC_MAX_DEPTH + 1][3][2];   /* per level: masks, colours, cones; one chunk each */
} mc_stream;

/* Starts reading a stream into buf (cap bytes). */
void mc_stream_init(mc_stream *s, uint8_t *buf, uint32_t cap);

/* Appends n bytes and checks every record they complete. Returns MC_STREAM_OK or the error that
 * stopped the stream (then and on every later call; the drawable prefix is kept). */
int mc_stream_feed(mc_stream *s, const uint8_t *data, uint32_t n);

/* The input has ended: MC_STREAM_OK when the stream was complete, else its error
 * (MC_STREAM_ERR_TRUNCATED when nothing else was wrong). */
int mc_stream_end(mc_stream *s);

/* The deepest drawable level (0: nothing drawable yet) and its octree (NULL then). The octree stays
 * valid while s and its buffer live; feeding more may deepen it. */
unsigned mc_stream_depth(const mc_stream *s);
const mc_octree *mc_stream_octree(const mc_stream *s);

/* A short name of an MC_STREAM_* code ("ok", "crc", ...). */
const char *mc_stream_error_name(int error);

/* CRC-32 (ISO-HDLC, as zlib's crc32) of n bytes, continuing from crc (0 to start). */
uint32_t mc_stream_crc32(uint32_t crc, const uint8_t *p, uint32_t n);

#endif
